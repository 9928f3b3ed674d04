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
import java.util.Set;

import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.impl.JidCreate;

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
    void defaultsApplyToEverySettingLeftOut() {
        ControlMlSettings s = ControlMlSettings.of(settings);
        assertEquals("127.0.0.1", s.server());
        assertEquals(5222, s.port());
        assertEquals("s3cret", s.password(), "the first line, without its line end");
        assertEquals("onboard", s.resource());
        assertEquals(Duration.ofSeconds(1), s.reconnectMin());
        assertEquals(Duration.ofSeconds(30), s.reconnectMax());
        assertEquals(Set.of(), s.operators());
        assertEquals(Duration.ofSeconds(5), s.staleCommandAfter()); // below the workbench's 10 s request timeout
        assertEquals("sabot-01", s.robotName(), "without robot.name, the JID's local part");
        assertTrue(!s.toString().contains("s3cret"), "the password is never printed");
    }

    @Test
    void operatorsAreACommaSeparatedListOfBareJids() throws Exception {
        settings.put("operators", " alice@sabot.local, bob@lab.example ,");
        assertEquals(Set.of(JidCreate.entityBareFrom("alice@sabot.local"), JidCreate.entityBareFrom(
                "bob@lab.example")), ControlMlSettings.of(settings).operators());
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
    void badOperatorIsRefusedNamingIt() {
        settings.put("operators", "alice@sabot.local, bob");
        assertOneProblem("operators", "'bob' in the operator list is not a bare JID (local@domain without a "
                + "resource, e.g. sabot-01@sabot.local)");
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
