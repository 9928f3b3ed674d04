package sabot.onboard.controlml.internal.session;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.nio.file.attribute.PosixFilePermission;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.EnumSet;
import java.util.Set;

/**
 * The robot's XMPP password, kept in a file that only its owner may read or write (like an ssh private key): the
 * first line of the file, without its line end. Anything else about the file is a configuration error.
 */
final class PasswordFile {

    /** Permissions that would let someone other than the owner read the password or replace it. */
    private static final Set<PosixFilePermission> SHARED = EnumSet.of(PosixFilePermission.GROUP_READ,
            PosixFilePermission.GROUP_WRITE, PosixFilePermission.OTHERS_READ, PosixFilePermission.OTHERS_WRITE);

    /** Why a password file cannot be used; the message is for the operator and says how to fix it. */
    static final class Refused extends Exception {
        private static final long serialVersionUID = 1L;

        Refused(String message) {
            super(message);
        }
    }

    private PasswordFile() {
    }

    /**
     * @param file the password file (absolute, or relative to the working directory)
     * @return the password; never empty
     * @throws Refused when the file is missing, not a regular file, unreadable, shared with group or others, or empty
     */
    static String read(Path file) throws Refused {
        if (!Files.exists(file)) {
            throw new Refused("password file " + file + " does not exist");
        }
        if (!Files.isRegularFile(file)) {
            throw new Refused(file + " is not a regular file");
        }
        Set<PosixFilePermission> permissions;
        try {
            permissions = Files.getPosixFilePermissions(file);
        } catch (UnsupportedOperationException | IOException e) {
            throw new Refused("cannot read the permissions of " + file + " (" + e + "); it must be a file on a POSIX "
                    + "file system, readable by its owner only");
        }
        if (!Files.isReadable(file)) {
            throw new Refused(file + " is not readable by this process (user " + System.getProperty("user.name")
                    + ", file mode " + mode(permissions) + ")");
        }
        if (permissions.stream().anyMatch(SHARED::contains)) {
            throw new Refused(file + " is readable or writable by group or others (mode " + mode(permissions)
                    + "); make it private: chmod 600 " + file);
        }
        String text;
        try {
            text = Files.readString(file, StandardCharsets.UTF_8);
        } catch (IOException e) {
            throw new Refused("cannot read " + file + ": " + e.getMessage());
        }
        String password = text.lines().findFirst().orElse("");
        if (password.isEmpty()) {
            throw new Refused("password file " + file + " is empty (the password is its first line)");
        }
        return password;
    }

    /**
     * Writes {@code password} into a new file beside {@code file}, readable and writable by its owner only: the
     * first half of a replacement ({@link #commit}), done before the server is asked, so that a folder the process
     * cannot write is found while the old password still works.
     *
     * @return the new file
     */
    static Path prepare(Path file, String password) throws IOException {
        Path temporary = Files.createTempFile(file.toAbsolutePath().getParent(), "." + file.getFileName(), ".new",
                PosixFilePermissions.asFileAttribute(EnumSet.of(PosixFilePermission.OWNER_READ,
                        PosixFilePermission.OWNER_WRITE)));
        try {
            Files.writeString(temporary, password + "\n", StandardCharsets.UTF_8);
            return temporary;
        } catch (IOException e) {
            Files.deleteIfExists(temporary);
            throw e;
        }
    }

    /** Puts the file {@link #prepare} wrote in the place of {@code file}, in one step (a rename). */
    static void commit(Path prepared, Path file) throws IOException {
        Files.move(prepared, file, StandardCopyOption.ATOMIC_MOVE, StandardCopyOption.REPLACE_EXISTING);
    }

    /** @return the permissions as an octal mode, e.g. {@code 0644} */
    static String mode(Set<PosixFilePermission> permissions) {
        String rwx = PosixFilePermissions.toString(permissions);
        int mode = 0;
        for (int i = 0; i < 9; i++) {
            mode = mode << 1 | (rwx.charAt(i) == '-' ? 0 : 1);
        }
        return String.format("%04o", mode);
    }
}
