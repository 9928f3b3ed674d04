package sabot.model.robot;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.io.InputStream;
import java.net.URL;
import java.nio.file.Files;
import java.nio.file.Path;

import org.junit.jupiter.api.Test;
import org.osgi.framework.Bundle;
import org.osgi.framework.FrameworkUtil;

/**
 * The reference robot's description has one source, docs/sabot-robot.properties beside the Modbus map; the build
 * copies it into sabot.model. These tests run in OSGi against the built bundle, so they prove it got there.
 */
class RobotDescriptionsResourceTest {

    private static final String ENTRY = "sabot/model/robot/" + RobotDescriptions.DEFAULT_RESOURCE;

    @Test
    void theBundleCarriesTheDescriptionFromDocs() throws IOException {
        Bundle model = FrameworkUtil.getBundle(RobotDescriptions.class);
        assertNotNull(model, "sabot.model is not running as an OSGi bundle");
        URL entry = model.getEntry(ENTRY);
        assertNotNull(entry, ENTRY + " is missing from the sabot.model bundle");
        byte[] bundled;
        try (InputStream in = entry.openStream()) {
            bundled = in.readAllBytes();
        }
        assertArrayEquals(Files.readAllBytes(docsFile()), bundled,
                "the bundled description differs from docs/sabot-robot.properties: rebuild sabot.model");
    }

    @Test
    void defaultsAreTheReferenceRobot() throws IOException {
        RobotDescription defaults = RobotDescriptions.defaults();
        assertEquals(RobotDescriptions.load(docsFile()), defaults);
        assertEquals("sabot-reference", defaults.name());
        assertEquals(43, defaults.gearRatio());
        assertEquals(512, defaults.encoderLines());
        // Vs / Ke of the Maxon A-max 32 24 V winding (Kt = Ke = 29.6 mNm/A), which the simulator's motor reaches
        assertEquals(24 / 0.0296 * 60 / (2 * Math.PI), defaults.motorNoLoadSpeedRpm(), 5);
    }

    /** docs/sabot-robot.properties, found from the test's working directory upward (it is inside the checkout). */
    private static Path docsFile() {
        for (Path dir = Path.of("").toAbsolutePath(); dir != null; dir = dir.getParent()) {
            Path candidate = dir.resolve("docs").resolve(RobotDescriptions.DEFAULT_RESOURCE);
            if (Files.isRegularFile(candidate)) {
                return candidate;
            }
        }
        assertTrue(false, "no docs/" + RobotDescriptions.DEFAULT_RESOURCE + " above " + Path.of("").toAbsolutePath());
        return null;
    }
}
