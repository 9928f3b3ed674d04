package sabot.onboard.controlml.internal.session;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Duration;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.Role;
import sabot.fleet.AccessRules;
import sabot.onboard.task.InvalidSettings;
import sabot.onboard.task.TaskSettingsCheck.Problem;

/** The controlml settings: every problem Metatype cannot catch is refused with its own message. */
class ControlMlSettingsTest {

    @TempDir
    Path dir;
    Path passwordFile;
    Map<String, Object> settings;

    @BeforeEach
    void validSettings() throws Exception {
        passwordFile = privateFile("robot.pw", "s3cret\n");
        settings = new HashMap<>(Map.of("jid", "sabot-01@sabot.local", "passwordFile", passwordFile.toString()));
    }

    Path privateFile(String name, String content) throws Exception {
        Path f = dir.resolve(name);
        Files.writeString(f, content);
        Files.setPosixFilePermissions(f, PosixFilePermissions.fromString("rw-------"));
        return f;
    }

    List<Problem> problems() {
        return ControlMlSettings.problems(settings);
    }

    void assertOneProblem(String setting, String message) {
        assertEquals(List.of(new Problem(setting, message)), problems());
    }

    @Test
    void defaultsApplyToEverySettingLeftOut() throws Exception {
        ControlMlSettings s = ControlMlSettings.of(settings);
        assertEquals(List.of("127.0.0.1"), s.servers());
        assertEquals(5222, s.port());
        assertEquals("s3cret", s.password(), "the first line, without its line end");
        assertEquals("onboard", s.resource());
        assertEquals(Duration.ofSeconds(1), s.reconnectMin());
        assertEquals(Duration.ofSeconds(30), s.reconnectMax());
        // deny by default: roles only from the lab's server groups, one per role, and the lab's robots observers
        assertEquals(false, s.open());
        for (Role role : List.of(Role.OPERATOR, Role.MAINTAINER)) {
            assertEquals(Set.of(AccessRules.LAB_GROUPS.get(role)), s.access().groupsOf(role), role.label());
        }
        assertEquals(Set.of(AccessRules.OBSERVERS_GROUP, AccessRules.ROBOTS_GROUP), s.access().groupsOf(
                Role.OBSERVER));
        assertEquals(Role.NONE, s.access().roleOf(JidCreate.bareFrom("alice@sabot.local"), Set.of("friends")));
        assertEquals(Optional.empty(), s.lobby(), "no fleet lobby unless one is configured");
        assertEquals(Duration.ofSeconds(5), s.staleCommandAfter()); // below the workbench's 10 s request timeout
        assertEquals("sabot-01", s.robotName(), "without robot.name, the JID's local part");
        assertTrue(!s.toString().contains("s3cret"), "the password is never printed");
    }

    @Test
    void roleGroupsAreCommaSeparatedListsAndTheHighestGrantedRoleCounts() throws Exception {
        settings.put("operatorGroups", " lab-ops, night shift ,");
        settings.put("maintainerGroups", "sabot-01-maintainers");
        settings.put("observerGroups", "");
        ControlMlSettings s = ControlMlSettings.of(settings);
        assertEquals(Set.of("lab-ops", "night shift"), s.access().groupsOf(Role.OPERATOR));
        assertEquals(Set.of(), s.access().groupsOf(Role.OBSERVER));
        var alice = JidCreate.bareFrom("alice@sabot.local");
        assertEquals(Role.OPERATOR, s.access().roleOf(alice, Set.of("night shift")));
        assertEquals(Role.MAINTAINER, s.access().roleOf(alice, Set.of("lab-ops", "sabot-01-maintainers")));
        assertEquals(Role.NONE, s.access().roleOf(alice, Set.of("sabot-maintainers")), "not a group of this robot");
    }

    @Test
    void noGroupAtAllIsRefusedUnlessThePolicyIsOpenExplicitly() {
        settings.put("observerGroups", "");
        settings.put("operatorGroups", " ");
        settings.put("maintainerGroups", "");
        assertOneProblem("maintainerGroups", "no group holds a role, so nobody could command this robot: name the "
                + "lab's maintainer group (or set openPolicy = true, for a lab whose server admits only its own "
                + "people)");
        settings.put("openPolicy", "true");
        ControlMlSettings s = ControlMlSettings.of(settings);
        assertTrue(s.open());
        assertTrue(s.toString().contains("roles open"), s.toString());
    }

    @Test
    void passwordFileReadableByOthersIsRefusedSayingHowToFixIt() throws Exception {
        Files.setPosixFilePermissions(passwordFile, PosixFilePermissions.fromString("rw-r--r--"));
        assertOneProblem("passwordFile", passwordFile + " is readable or writable by group or others (mode 0644); "
                + "make it private: chmod 600 " + passwordFile);
    }

    @Test
    void passwordFileWritableByGroupIsRefused() throws Exception {
        Files.setPosixFilePermissions(passwordFile, PosixFilePermissions.fromString("rw--w----"));
        assertOneProblem("passwordFile", passwordFile + " is readable or writable by group or others (mode 0620); "
                + "make it private: chmod 600 " + passwordFile);
    }

    @Test
    void missingPasswordFileIsRefused() {
        settings.put("passwordFile", dir.resolve("nope.pw").toString());
        assertOneProblem("passwordFile", "password file " + dir.resolve("nope.pw") + " does not exist");
    }

    @Test
    void passwordFileThatIsADirectoryIsRefused() {
        settings.put("passwordFile", dir.toString());
        assertOneProblem("passwordFile", dir + " is not a regular file");
    }

    @Test
    void emptyPasswordFileIsRefused() throws Exception {
        settings.put("passwordFile", privateFile("empty.pw", "\n").toString());
        assertOneProblem("passwordFile", "password file " + dir.resolve("empty.pw")
                + " is empty (the password is its first line)");
    }

    @Test
    void missingAccountAndPasswordFileAreBothReported() {
        settings.clear();
        assertEquals(List.of(new Problem("jid", "no account given (the robot's bare JID, e.g. sabot-01@sabot.local)"),
                new Problem("passwordFile", "no password file given")), problems());
    }

    @Test
    void jidWithAResourceOrWithoutALocalPartIsRefused() {
        for (String bad : new String[] { "sabot-01@sabot.local/onboard", "sabot.local", "@sabot.local" }) {
            settings.put("jid", bad);
            assertOneProblem("jid", "'" + bad
                    + "' is not a bare JID (local@domain without a resource, e.g. sabot-01@sabot.local)");
        }
    }

    @Test
    void theFleetLobbyIsARoomsBareJidAndAnythingElseIsRefused() throws Exception {
        settings.put("lobby", " fleet@conference.sabot.local ");
        assertEquals(Optional.of(JidCreate.entityBareFrom("fleet@conference.sabot.local")), ControlMlSettings.of(
                settings).lobby());
        for (String bad : new String[] { "fleet@conference.sabot.local/robot", "conference.sabot.local" }) {
            settings.put("lobby", bad);
            assertOneProblem("lobby", "'" + bad + "' is not a bare JID (local@domain without a resource, e.g. "
                    + "fleet@conference.sabot.local)");
        }
        settings.put("lobby", " ");
        assertEquals(Optional.empty(), ControlMlSettings.of(settings).lobby(), "blank: no lobby");
    }

    @Test
    void aGroupNameWithAControlCharacterIsRefusedNamingIt() {
        settings.put("operatorGroups", "lab-ops, bad\u0007name");
        assertOneProblem("operatorGroups", "group name 'bad?name' has a control character");
    }

    @Test
    void severalServersAreACommaSeparatedListAndABadOneIsNamed() throws Exception {
        settings.put("server", " 127.0.0.1, 127.0.0.2 ,lab-2.example");
        assertEquals(List.of("127.0.0.1", "127.0.0.2", "lab-2.example"), ControlMlSettings.of(settings).servers());
        settings.put("server", "127.0.0.1,,lab 2");
        assertEquals(List.of(new Problem("server", "'' is not a server (a host name or an IP address; several, "
                + "comma-separated)"), new Problem("server", "'lab 2' is not a server (a host name or an IP address; "
                        + "several, comma-separated)")), problems());
    }

    @Test
    void reconnectMaxBelowReconnectMinIsRefused() {
        settings.put("reconnectMin", 5.0);
        settings.put("reconnectMax", 1.0);
        assertOneProblem("reconnectMax", "reconnectMax (1.0 s) is below reconnectMin (5.0 s)");
    }

    @Test
    void activationWithBadSettingsFailsNamingEveryKey() {
        settings.put("jid", "nobody");
        settings.put("passwordFile", dir.resolve("nope.pw").toString());
        InvalidSettings e = assertThrows(InvalidSettings.class, () -> ControlMlSettings.of(settings));
        assertEquals("task 'controlml' not started: key 'controlml.jid': 'nobody' is not a bare JID (local@domain "
                + "without a resource, e.g. sabot-01@sabot.local); key 'controlml.passwordFile': password file "
                + dir.resolve("nope.pw") + " does not exist", e.getMessage());
    }

    @Test
    void backoffDoublesFromTheMinimumUpToTheMaximum() {
        Duration min = Duration.ofMillis(500);
        Duration max = Duration.ofSeconds(3);
        assertEquals(List.of(500L, 1000L, 2000L, 3000L, 3000L), List.of(1, 2, 3, 4, 50).stream().map(
                n -> ControlMlSession.backoff(n, min, max).toMillis()).toList());
    }
}
