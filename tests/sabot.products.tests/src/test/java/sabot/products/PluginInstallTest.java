package sabot.products;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.List;
import java.util.stream.Stream;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The optional diagnostics plug-in installs from the built p2 update site into a copy of the materialized workbench
 * with the p2 director, and is active at the next start; the uninstalled copy has no such plug-in (control).
 * Starts real workbench windows: needs the X display that ./sabot test provides (Xvfb).
 */
class PluginInstallTest {

    private static final String FEATURE_IU = "sabot.workbench.diagnostics.feature.feature.group";
    private static final String ACTIVE_LINE = "Sabot diagnostics plug-in";

    @TempDir
    Path dir;

    @Test
    void diagnosticsFeatureInstallsFromTheUpdateSiteAndIsActiveAfterRestart() throws Exception {
        assertTrue(System.getenv("DISPLAY") != null, "no X display: run under xvfb-run (./sabot test does)");
        Path workbench = copy(ProductProcess.product("sabot.workbench.product", "sabot-workbench"), dir.resolve(
                "workbench"));
        Path site = ProductProcess.root().resolve("product/sabot.site/target/repository");
        Path director = ProductProcess.product("sabot.director.product", "sabot-director");

        try (ProductProcess before = startWorkbench(workbench)) {
            assertEquals(0, before.waitFor(), before.output());
            assertFalse(before.output().contains(ACTIVE_LINE), "plug-in active before it was installed");
        }

        try (ProductProcess install = ProductProcess.start(director, List.of(), List.of(
                "-application", "org.eclipse.equinox.p2.director",
                "-repository", site.toUri().toString(),
                "-installIU", FEATURE_IU,
                "-destination", workbench.toString(),
                "-profile", "DefaultProfile"))) {
            assertEquals(0, install.waitFor(), install.output());
            assertTrue(install.output().contains("Operation completed"), install.output());
        }
        String bundles = Files.readString(workbench.resolve(
                "configuration/org.eclipse.equinox.simpleconfigurator/bundles.info"));
        assertTrue(bundles.lines().anyMatch(l -> l.startsWith("sabot.workbench.diagnostics,") && l.endsWith(
                ",4,true")), "not in bundles.info as started:\n" + bundles);

        try (ProductProcess after = startWorkbench(workbench)) {
            assertEquals(0, after.waitFor(), after.output());
            assertTrue(after.output().contains(ACTIVE_LINE), after.output());
        }
    }

    /**
     * The update site alone is enough to install Sabot Onboard into a bare Equinox with p2 (a copy of the director
     * product): its features list what products otherwise get through autoIncludeRequirements — the OSGi service APIs
     * of the base runtime, and ControlML with the whole Smack client that the session and remote FS tasks need. The
     * installed runtime then runs as the onboard application: the tasks the file enables start from their own task
     * bundles (the runtime's heartbeat, the ControlML session's bundle, the remote FS's bundle).
     */
    @Test
    void onboardFeatureInstallsFromTheUpdateSiteIntoABareRuntime() throws Exception {
        Path director = ProductProcess.product("sabot.director.product", "sabot-director");
        Path target = copy(director, dir.resolve("runtime"));
        Path site = ProductProcess.root().resolve("product/sabot.site/target/repository");
        Path bundlesInfo = target.resolve("configuration/org.eclipse.equinox.simpleconfigurator/bundles.info");
        List<String> needed = List.of("sabot.onboard", "sabot.onboard.controlml", "sabot.onboard.remotefs",
                "sabot.controlml", "sabot.model", "smack-core", "smack-tcp",
                "smack-streammanagement", "smack-xmlparser-xpp3", "smack-java8", "smack-resolver-javax",
                "org.osgi.service.cm", "org.apache.felix.scr");
        String before = Files.readString(bundlesInfo);
        assertFalse(needed.stream().allMatch(b -> before.lines().anyMatch(l -> l.startsWith(b + ","))),
                "the bare runtime had everything before the install");

        try (ProductProcess install = ProductProcess.start(director, List.of(), List.of(
                "-application", "org.eclipse.equinox.p2.director",
                "-repository", site.toUri().toString(),
                "-installIU", "sabot.onboard.feature.feature.group",
                "-destination", target.toString(),
                "-profile", "DefaultProfile"))) {
            assertEquals(0, install.waitFor(), install.output());
            assertTrue(install.output().contains("Operation completed"), install.output());
        }
        String bundles = Files.readString(bundlesInfo);
        for (String bundle : needed) {
            assertTrue(bundles.lines().anyMatch(l -> l.startsWith(bundle + ",")), bundle + " not installed:\n"
                    + bundles);
        }

        // configured, the installed tasks start (no XMPP server listens: the session keeps trying in the background)
        Path password = dir.resolve("robot.pw");
        Files.writeString(password, "secret\n");
        Files.setPosixFilePermissions(password, PosixFilePermissions.fromString("rw-------"));
        Path root = Files.createDirectories(dir.resolve("files"));
        Path config = dir.resolve("onboard.conf");
        Files.writeString(config, String.join("\n", "robot.name = lab-07", "tasks = heartbeat, controlml, remotefs",
                "controlml.jid = lab-07@sabot.local", "controlml.passwordFile = " + password,
                "controlml.server = 127.0.0.1", "controlml.port = " + unusedPort(), "remotefs.root = " + root, ""));
        try (ProductProcess onboard = ProductProcess.start(target, List.of(), List.of("-application",
                "sabot.onboard.application", "-config", config.toString()))) {
            String loaded = onboard.await(l -> l.contains("task(s) loaded") || l.contains("did not start"),
                    "the tasks loaded");
            assertTrue(loaded.endsWith("running as 'lab-07': 3 task(s) loaded: heartbeat, controlml, remotefs"),
                    onboard.output());
            onboard.terminate();
            assertEquals(0, onboard.waitFor(), onboard.output());
        }
    }

    /** @return a loopback TCP port nobody listens on (bound and released) */
    private static int unusedPort() throws IOException {
        try (ServerSocket s = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            return s.getLocalPort();
        }
    }

    private ProductProcess startWorkbench(Path workbench) throws IOException {
        return ProductProcess.start(workbench, List.of(), List.of("-data", dir.resolve("workspace").toString(),
                "-sabot.exit"));
    }

    /** Copies a materialized product (installs change it). */
    static Path copy(Path from, Path to) throws IOException {
        try (Stream<Path> files = Files.walk(from)) {
            for (Path p : (Iterable<Path>) files::iterator) {
                Path target = to.resolve(from.relativize(p).toString());
                if (Files.isDirectory(p)) {
                    Files.createDirectories(target);
                } else {
                    Files.copy(p, target, StandardCopyOption.COPY_ATTRIBUTES);
                }
            }
        }
        return to;
    }
}
