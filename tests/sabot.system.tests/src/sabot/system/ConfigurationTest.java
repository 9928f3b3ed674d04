package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import sabot.testsupport.robot.OnboardProcess;

/**
 * Proof 8: a configuration that cannot work stops the product before anything starts, with one line naming the file,
 * the line and the key, and exit status 2. No server or simulator is needed: the checks run before any task.
 */
class ConfigurationTest {

    static final double[] START = RigTest.WEST_OF_PARTITION;

    @Test
    void unknownSerialPortIsAConfigurationError(@TempDir Path dir) throws Exception {
        assertRefused(dir, "/dev/ttyNOSUCHPORT", null, "rw-------", "bus.port", "/dev/ttyNOSUCHPORT");
    }

    @Test
    void missingMapIsAConfigurationError(@TempDir Path dir) throws Exception {
        assertRefused(dir, null, dir.resolve("no-such-map.yaml").toString(), "rw-------", "planner.map",
                "no-such-map.yaml");
    }

    @Test
    void passwordFileReadableByOthersIsAConfigurationError(@TempDir Path dir) throws Exception {
        assertRefused(dir, null, null, "rw-r--r--", "controlml.passwordFile", "xmpp-password");
    }

    private static void assertRefused(Path dir, String port, String map, String passwordMode, String key,
            String named) throws Exception {
        Path device = dir.resolve("pty-stand-in");
        Files.writeString(device, ""); // the port check is only about existence here; nothing opens it
        Path passwordFile = dir.resolve("xmpp-password");
        Files.writeString(passwordFile, "pw\n");
        Files.setPosixFilePermissions(passwordFile, PosixFilePermissions.fromString(passwordMode));
        String text = OnboardProcess.configuration(new OnboardProcess.Robot("r1", port == null ? device.toString()
                : port, START, 5222, null), passwordFile, Files.createDirectories(dir.resolve("fs")),
                "");
        if (map != null) {
            text = text.replaceFirst("(?m)^planner\\.map = .*$", "planner.map = " + map);
        }
        Path config = dir.resolve("onboard.conf");
        Files.writeString(config, text);
        try (OnboardProcess p = OnboardProcess.start(config)) {
            assertEquals(2, p.waitFor(), p.output());
            List<String> errors = p.output().lines().filter(l -> l.contains("ERROR")).toList();
            assertEquals(1, errors.size(), p.output());
            String line = errors.get(0);
            assertTrue(line.contains("configuration error: " + config), line);
            assertTrue(line.contains("key '" + key + "'"), line);
            assertTrue(line.contains(named), line);
        }
    }
}
