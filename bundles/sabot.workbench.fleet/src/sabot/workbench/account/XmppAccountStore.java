package sabot.workbench.account;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.AtomicMoveNotSupportedException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.List;
import java.nio.file.StandardCopyOption;
import java.nio.file.attribute.PosixFilePermission;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.EnumSet;
import java.util.Set;

import org.eclipse.core.runtime.preferences.IEclipsePreferences;
import org.eclipse.core.runtime.preferences.InstanceScope;
import org.osgi.service.prefs.BackingStoreException;
import org.osgi.service.prefs.Preferences;

/**
 * Stores the XMPP account: server, port, JID and CA file in the workbench's preferences, the password in a separate file
 * readable by its owner only (mode 0600, like an SSH key), never in the preferences. The file is replaced
 * atomically and refused when its permissions are looser than 0600.
 */
public final class XmppAccountStore {

    /** The instance-scope preference node of the workbench's account (the core bundle's name, kept for saved data). */
    public static final String NODE = "sabot.workbench";
    /** System property overriding the folder of the password file (default {@code ~/.sabot/workbench}). */
    public static final String SECRETS_DIR_PROPERTY = "sabot.workbench.secrets";
    /** Preference keys; every key of the account starts with {@link #KEY_PREFIX}. */
    public static final String KEY_PREFIX = "xmpp.";
    static final String KEY_SERVER = KEY_PREFIX + "server";
    static final String KEY_PORT = KEY_PREFIX + "port";
    static final String KEY_JID = KEY_PREFIX + "jid";
    static final String KEY_CA_FILE = KEY_PREFIX + "caFile";
    /** The robots to follow besides those already in the roster (fleet rule 12): bare JIDs, comma-separated. */
    static final String KEY_ROBOTS = KEY_PREFIX + "robots";
    /**
     * The fleet lobby (roster rule 11): the bare JID of a multi-user chat room, e.g.
     * {@code fleet@conference.sabot.local}, where online robots are discovered; empty for none.
     */
    static final String KEY_LOBBY = KEY_PREFIX + "lobby";
    private static final Set<PosixFilePermission> OWNER_ONLY = EnumSet.of(PosixFilePermission.OWNER_READ,
            PosixFilePermission.OWNER_WRITE);

    private final Preferences preferences;
    private final Path passwordFile;

    /**
     * @param preferences  where the non-secret fields go (the bundle's instance-scope preferences)
     * @param passwordFile where the password goes, e.g. {@code ~/.sabot/workbench/xmpp-password}
     */
    public XmppAccountStore(Preferences preferences, Path passwordFile) {
        this.preferences = preferences;
        this.passwordFile = passwordFile;
    }

    /**
     * @return the store the workbench uses: the instance-scope node {@link #NODE}, the password in
     *         {@code xmpp-password} of the folder named by {@link #SECRETS_DIR_PROPERTY} or {@code ~/.sabot/workbench}
     */
    public static XmppAccountStore workbenchStore() {
        return new XmppAccountStore(workbenchNode(), defaultPasswordFile());
    }

    /** @return the preference node the workbench's account lives in (listen to it for changes) */
    public static IEclipsePreferences workbenchNode() {
        return InstanceScope.INSTANCE.getNode(NODE);
    }

    /** @return where the workbench keeps the password unless told otherwise */
    public static Path defaultPasswordFile() {
        String dir = System.getProperty(SECRETS_DIR_PROPERTY);
        Path secrets = dir != null ? Paths.get(dir) : Paths.get(System.getProperty("user.home"), ".sabot",
                "workbench");
        return secrets.resolve("xmpp-password");
    }

    /**
     * @return the robots to follow besides the roster's (fleet rule 12), as stored: bare JIDs in the order given;
     *         empty when none
     */
    public List<String> loadRobots() {
        List<String> robots = new ArrayList<>();
        for (String item : preferences.get(KEY_ROBOTS, "").split(",")) {
            if (!item.isBlank()) {
                robots.add(item.strip());
            }
        }
        return robots;
    }

    /**
     * Stores the robots to follow.
     *
     * @throws IllegalArgumentException naming the first entry that is not a bare JID (nothing is stored then)
     * @throws IOException              when the preferences cannot be written
     */
    public void saveRobots(List<String> robots) throws IOException {
        for (String r : robots) {
            String problem = new XmppAccount("server", XmppAccount.DEFAULT_PORT, r).problem();
            if (problem != null) {
                throw new IllegalArgumentException("robot '" + r + "': " + problem);
            }
        }
        preferences.put(KEY_ROBOTS, String.join(",", robots));
        flush();
    }

    /** @return the fleet lobby's room (bare JID) as stored, or "" when none is configured */
    public String loadLobby() {
        return preferences.get(KEY_LOBBY, "").strip();
    }

    /**
     * Stores the fleet lobby (roster rule 11).
     *
     * @param room the room's bare JID, e.g. {@code fleet@conference.sabot.local}; "" or null for none
     * @throws IllegalArgumentException when the room is not a bare JID (nothing is stored then)
     * @throws IOException              when the preferences cannot be written
     */
    public void saveLobby(String room) throws IOException {
        String r = room == null ? "" : room.strip();
        if (!r.isEmpty()) {
            String problem = new XmppAccount("server", XmppAccount.DEFAULT_PORT, r).problem();
            if (problem != null) {
                throw new IllegalArgumentException("lobby '" + r + "': " + problem);
            }
        }
        if (r.isEmpty()) {
            preferences.remove(KEY_LOBBY);
        } else {
            preferences.put(KEY_LOBBY, r);
        }
        flush();
    }

    private void flush() throws IOException {
        try {
            preferences.flush();
        } catch (BackingStoreException e) {
            throw new IOException("cannot save the XMPP account preferences: " + e.getMessage(), e);
        }
    }

    /** @return the stored account; empty fields and the default port when nothing is stored */
    public XmppAccount load() {
        return new XmppAccount(preferences.get(KEY_SERVER, ""), preferences.getInt(KEY_PORT,
                XmppAccount.DEFAULT_PORT), preferences.get(KEY_JID, ""), preferences.get(KEY_CA_FILE, ""));
    }

    /**
     * Saves the account and, when {@code password} is not null, the password. Nothing is written when the account
     * is invalid.
     *
     * @throws IllegalArgumentException with {@link XmppAccount#problem()} when the account is invalid
     * @throws IOException              when the preferences or the password file cannot be written
     */
    public void save(XmppAccount account, char[] password) throws IOException {
        String problem = account.problem();
        if (problem != null) {
            throw new IllegalArgumentException(problem);
        }
        if (password != null) {
            writePassword(password);
        }
        preferences.put(KEY_SERVER, account.server());
        preferences.putInt(KEY_PORT, account.port());
        preferences.put(KEY_JID, account.jid());
        if (account.caFile().isEmpty()) {
            preferences.remove(KEY_CA_FILE);
        } else {
            preferences.put(KEY_CA_FILE, account.caFile());
        }
        flush();
    }

    /** @return true when a password has been stored */
    public boolean hasPassword() {
        return Files.isRegularFile(passwordFile);
    }

    /**
     * @return the stored password, or null when none is stored
     * @throws IOException when the file is readable by others than its owner (it is not used then)
     */
    public char[] loadPassword() throws IOException {
        if (!Files.isRegularFile(passwordFile)) {
            return null;
        }
        Set<PosixFilePermission> perms = Files.getPosixFilePermissions(passwordFile);
        if (!OWNER_ONLY.containsAll(perms)) {
            throw new IOException(passwordFile + " has permissions " + PosixFilePermissions.toString(perms)
                    + "; it must be rw------- (chmod 600)");
        }
        return new String(Files.readAllBytes(passwordFile), StandardCharsets.UTF_8).toCharArray();
    }

    /** Removes the stored password. */
    public void forgetPassword() throws IOException {
        Files.deleteIfExists(passwordFile);
    }

    /** @return where the password is kept */
    public Path passwordFile() {
        return passwordFile;
    }

    private void writePassword(char[] password) throws IOException {
        Path dir = passwordFile.toAbsolutePath().getParent();
        Files.createDirectories(dir, PosixFilePermissions.asFileAttribute(EnumSet.of(PosixFilePermission.OWNER_READ,
                PosixFilePermission.OWNER_WRITE, PosixFilePermission.OWNER_EXECUTE)));
        // Created 0600 from the start (no window in which another user could open it), then moved into place.
        Path tmp = Files.createTempFile(dir, ".xmpp-password", ".tmp", PosixFilePermissions.asFileAttribute(
                OWNER_ONLY));
        try {
            Files.write(tmp, new String(password).getBytes(StandardCharsets.UTF_8));
            try {
                Files.move(tmp, passwordFile, StandardCopyOption.REPLACE_EXISTING, StandardCopyOption.ATOMIC_MOVE);
            } catch (AtomicMoveNotSupportedException e) {
                Files.move(tmp, passwordFile, StandardCopyOption.REPLACE_EXISTING);
            }
        } finally {
            Files.deleteIfExists(tmp);
        }
    }
}
