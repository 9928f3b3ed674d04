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
     * The update site alone is enough to build a robot's product task by task in a bare Equinox with p2 (a copy of the
     * director product). First the onboard runtime feature: it brings what products otherwise get through
     * autoIncludeRequirements (the OSGi service APIs, ControlML with the whole Smack client) and configuration units
     * that start them, and it runs its own heartbeat task; a file that enables a task no installed bundle provides is
     * refused by name. Then two task bundles, installed one by one as the site's bundle units (p2 adds the libraries
     * they import): the same file now starts every task it enables, each from its own bundle, and the motion tasks,
     * never installed, are still absent.
     */
    @Test
    void taskBundlesInstallFromTheUpdateSiteIntoABareOnboardRuntimeAndStart() throws Exception {
        Path director = ProductProcess.product("sabot.director.product", "sabot-director");
        Path target = copy(director, dir.resolve("runtime"));
        Path bundlesInfo = target.resolve("configuration/org.eclipse.equinox.simpleconfigurator/bundles.info");
        List<String> runtime = List.of("sabot.onboard", "sabot.controlml", "sabot.model", "smack-core", "smack-tcp",
                "smack-streammanagement", "smack-xmlparser-xpp3", "smack-java8", "smack-resolver-javax",
                "org.osgi.service.cm", "org.apache.felix.scr");
        List<String> tasks = List.of("sabot.onboard.controlml", "sabot.onboard.remotefs");
        String before = Files.readString(bundlesInfo);
        assertFalse(runtime.stream().allMatch(b -> installed(before, b)), "the bare runtime had everything before");

        install(director, target, "sabot.onboard.runtime.feature.feature.group");
        String afterRuntime = Files.readString(bundlesInfo);
        for (String bundle : runtime) {
            assertTrue(installed(afterRuntime, bundle), bundle + " not installed:\n" + afterRuntime);
        }
        for (String bundle : List.of("sabot.onboard.controlml", "sabot.onboard.remotefs", "sabot.onboard.motion")) {
            assertFalse(installed(afterRuntime, bundle), bundle + " came with the runtime feature");
        }
        Path config = taskConfig();
        try (ProductProcess onboard = startOnboard(target, config)) {
            assertEquals(2, onboard.waitFor(), onboard.output());
            assertTrue(onboard.output().contains("key 'tasks': unknown task 'controlml' (available: heartbeat)"),
                    onboard.output());
        }

        install(director, target, tasks.toArray(String[]::new));
        String afterTasks = Files.readString(bundlesInfo);
        for (String bundle : tasks) {
            assertTrue(afterTasks.lines().anyMatch(l -> l.startsWith(bundle + ",") && l.endsWith(",4,true")),
                    bundle + " not installed as started:\n" + afterTasks);
        }
        assertFalse(installed(afterTasks, "sabot.onboard.motion"), "the motion tasks came with the task bundles");

        // no XMPP server listens: the session keeps trying in the background, and the tasks are running
        try (ProductProcess onboard = startOnboard(target, config)) {
            String loaded = onboard.await(l -> l.contains("task(s) loaded") || l.contains("did not start"),
                    "the tasks loaded");
            assertTrue(loaded.endsWith("running as 'lab-07': 3 task(s) loaded: heartbeat, controlml, remotefs"),
                    onboard.output());
            onboard.terminate();
            assertEquals(0, onboard.waitFor(), onboard.output());
        }
    }

    private static boolean installed(String bundlesInfo, String bundle) {
        return bundlesInfo.lines().anyMatch(l -> l.startsWith(bundle + ","));
    }

    /** Installs installable units from the built update site into {@code target} with the p2 director. */
    private static void install(Path director, Path target, String... units) throws Exception {
        Path site = ProductProcess.root().resolve("product/sabot.site/target/repository");
        try (ProductProcess install = ProductProcess.start(director, List.of(), List.of(
                "-application", "org.eclipse.equinox.p2.director",
                "-repository", site.toUri().toString(),
                "-installIU", String.join(",", units),
                "-destination", target.toString(),
                "-profile", "DefaultProfile"))) {
            assertEquals(0, install.waitFor(), install.output());
            assertTrue(install.output().contains("Operation completed"), install.output());
        }
    }

    /** @return a configuration file enabling the heartbeat, the ControlML session and the remote FS */
    private Path taskConfig() throws IOException {
        Path password = dir.resolve("robot.pw");
        Files.writeString(password, "secret\n");
        Files.setPosixFilePermissions(password, PosixFilePermissions.fromString("rw-------"));
        Path root = Files.createDirectories(dir.resolve("files"));
        Path config = dir.resolve("onboard.conf");
        Files.writeString(config, String.join("\n", "robot.name = lab-07", "tasks = heartbeat, controlml, remotefs",
                "controlml.jid = lab-07@sabot.local", "controlml.passwordFile = " + password,
                "controlml.server = 127.0.0.1", "controlml.port = " + unusedPort(), "remotefs.root = " + root, ""));
        return config;
    }

    private static ProductProcess startOnboard(Path runtime, Path config) throws IOException {
        return ProductProcess.start(runtime, List.of(), List.of("-application", "sabot.onboard.application",
                "-config", config.toString()));
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
