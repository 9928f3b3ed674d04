package sabot.products;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.DirectoryStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Properties;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import java.util.stream.Stream;
import java.util.zip.GZIPInputStream;
import java.util.zip.ZipEntry;
import java.util.zip.ZipInputStream;
import java.util.zip.ZipOutputStream;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The Eclipse update UI of Sabot Workbench, driven like an operator would, in a copy of the materialized (p2
 * director-installed) workbench started by its own start script under Xvfb:
 * <ol>
 * <li>Help lists Install New Software... and Check for Updates;</li>
 * <li>Install New Software... offers the preconfigured Sabot update site, lists its plug-ins category; the diagnostics
 * feature is checked, Next, Finish; the trust dialog for unsigned content is answered; Restart Now ends the workbench
 * with exit code 23 and the start script starts it again;</li>
 * <li>after that restart the feature is in the p2 profile and its bundle resolved; Check for Updates finds nothing
 * newer;</li>
 * <li>a second site holding the feature with a newer qualifier (published by this test with the p2 publisher, as a
 * rebuilt site would have it) is added; Check for Updates lists the newer version; Finish, trust, Restart Now; after
 * the restart the profile and the runtime have the new version; on the way, the splash showed its image with the
 * progress bar past a quarter and a "Loading &lt;plug-in&gt;" line.</li>
 * </ol>
 * The UI is driven from inside the workbench by tests/sabot.products.uidriver, a test bundle added to the copy through
 * {@code osgi.bundles} (in no feature, on no site). Screenshots go to docs/images: workbench-splash.png,
 * p2-install.png, p2-trust.png, p2-update.png.
 */
class P2UpdateUiTest {

    private static final String FEATURE = "sabot.workbench.diagnostics.feature";
    private static final String FEATURE_IU = FEATURE + ".feature.group";
    private static final String BUNDLE = "sabot.workbench.diagnostics";
    /** The category label and the site name as category.xml and sabot.workbench.p2.inf give them. */
    private static final String CATEGORY = "Sabot Workbench plug-ins";
    private static final String SITE_NAME = "Sabot update site";
    private static final String RESTARTING = "sabot-workbench: restarting";
    /** One run installs and restarts: two workbench starts plus the p2 work, on a busy 2-core machine. */
    private static final long RUN_TIMEOUT_S = 240;

    @TempDir
    Path dir;

    @Test
    void installNewSoftwareAndCheckForUpdatesWorkInTheDirectorInstalledWorkbench() throws Exception {
        assertTrue(System.getenv("DISPLAY") != null, "no X display: run under xvfb-run (./sabot test does)");
        Path workbench = PluginInstallTest.copy(ProductProcess.product("sabot.workbench.product", "sabot-workbench"),
                dir.resolve("workbench"));
        Path site = ProductProcess.root().resolve("product/sabot.site/target/repository");
        assertFalse(profile(workbench).contains("id='" + FEATURE_IU + "'"), "installed before the test");

        // 1-4: menu, install through the wizard, restart (23) by the start script, verify, no update
        String run1 = drive(workbench, "menu,install,verify,noupdate,exit", List.of());
        assertEquals(1, count(run1, RESTARTING), "one restart after the install:\n" + run1);
        for (String step : List.of("menu", "install", "verify", "noupdate", "exit")) {
            assertTrue(run1.contains("UIDRIVER " + step + " ok: "), step + " not done:\n" + run1);
        }
        assertTrue(line(run1, "UIDRIVER install ok: ").contains("'" + SITE_NAME + " - file:"), run1);
        assertTrue(line(run1, "UIDRIVER install ok: ").contains("osgi.bundle | " + BUNDLE) || line(run1,
                "UIDRIVER install ok: ").contains(BUNDLE), "trust dialog did not list the bundle:\n" + run1);
        String installed = versionIn(profile(workbench), FEATURE_IU);
        assertTrue(bundlesInfo(workbench).lines().anyMatch(l -> l.startsWith(BUNDLE + ",")), "bundle not in "
                + "bundles.info");

        // 5: a rebuilt site: the same feature and bundle with the qualifier one higher
        String[] bumped = publishBumped(site, installed, dir.resolve("site2"));
        String newFeature = bumped[0], newBundle = bumped[1];
        // the splash is checked here: from the second start on its bar knows how many bundles will start
        String run2 = drive(workbench, "splash,addsite,update,verifyupdate,exit", List.of(
                "-Dsabot.uidriver.site2=" + dir.resolve("site2").toUri(),
                "-Dsabot.uidriver.version=" + newFeature,
                "-Dsabot.uidriver.bundleVersion=" + newBundle));
        assertEquals(1, count(run2, RESTARTING), "one restart after the update:\n" + run2);
        for (String step : List.of("splash", "addsite", "update", "verifyupdate", "exit")) {
            assertTrue(run2.contains("UIDRIVER " + step + " ok: "), step + " not done:\n" + run2);
        }
        assertEquals(newFeature, versionIn(profile(workbench), FEATURE_IU), "profile after the update");
        assertTrue(bundlesInfo(workbench).lines().anyMatch(l -> l.startsWith(BUNDLE + "," + newBundle + ",")),
                "bundles.info after the update:\n" + bundlesInfo(workbench));
    }

    /**
     * Runs the workbench copy through its start script with the UI driver until the driver's last step closes it;
     * returns the console (both JVMs when it restarted).
     */
    private String drive(Path workbench, String steps, List<String> extra) throws Exception {
        Path driver = ProductProcess.root().resolve("tests/sabot.products.uidriver/target/"
                + "sabot.products.uidriver-0.1.0-SNAPSHOT.jar");
        assertTrue(Files.isRegularFile(driver), "UI driver not built: " + driver + " (run the tests reactor)");
        Properties config = new Properties();
        try (InputStream in = Files.newInputStream(workbench.resolve("configuration/config.ini"))) {
            config.load(in);
        }
        List<String> args = new ArrayList<>(List.of("-consoleLog", "-data", dir.resolve("workspace").toString(),
                "-vmargs",
                // the driver besides simpleconfigurator, kept although bundles.info does not list it
                "-Dosgi.bundles=" + config.getProperty("osgi.bundles") + ",reference:" + driver.toUri() + "@4:start",
                "-Dorg.eclipse.equinox.simpleconfigurator.exclusiveInstallation=false",
                "-Dsabot.uidriver.steps=" + steps,
                "-Dsabot.uidriver.state=" + dir.resolve("driver-" + steps.hashCode() + ".state"),
                "-Dsabot.uidriver.shots=" + ProductProcess.root().resolve("docs/images"),
                "-Dsabot.uidriver.feature=" + FEATURE,
                "-Dsabot.uidriver.bundle=" + BUNDLE,
                "-Dsabot.uidriver.category=" + CATEGORY,
                "-Dsabot.uidriver.siteName=" + SITE_NAME));
        args.addAll(extra);
        long t0 = System.nanoTime();
        try (ProductProcess p = ProductProcess.startScript(workbench, "sabot-workbench", args)) {
            int rc = p.waitFor(RUN_TIMEOUT_S);
            System.out.printf("P2UpdateUiTest: %s took %.1f s%n", steps, (System.nanoTime() - t0) / 1e9);
            assertFalse(p.output().contains("UIDRIVER FAILED"), p.output());
            assertEquals(0, rc, p.output());
            return p.output();
        }
    }

    /**
     * Publishes into {@code to} the feature and its bundle as the built site has them but with the qualifier one higher
     * (the p2 publisher application of the director product); returns {new feature version, new bundle version}.
     */
    private String[] publishBumped(Path site, String featureVersion, Path to) throws Exception {
        Path bundleJar = only(site.resolve("plugins"), BUNDLE + "_*.jar");
        String bundleVersion = bundleJar.getFileName().toString().replaceFirst("^" + Pattern.quote(BUNDLE) + "_", "")
                .replaceFirst("\\.jar$", "");
        String newFeature = bump(featureVersion);
        String newBundle = bump(bundleVersion);
        Path source = dir.resolve("site2-source");
        Files.createDirectories(source.resolve("features"));
        Files.createDirectories(source.resolve("plugins"));
        rewrite(site.resolve("features/" + FEATURE + "_" + featureVersion + ".jar"), source.resolve("features/" + FEATURE
                + "_" + newFeature + ".jar"), "feature.xml", text -> text
                        .replace("version=\"" + featureVersion + "\"", "version=\"" + newFeature + "\"")
                        .replace("version=\"" + bundleVersion + "\"", "version=\"" + newBundle + "\""));
        rewrite(bundleJar, source.resolve("plugins/" + BUNDLE + "_" + newBundle + ".jar"), "META-INF/MANIFEST.MF",
                text -> text.replace("Bundle-Version: " + bundleVersion, "Bundle-Version: " + newBundle));
        Path director = ProductProcess.product("sabot.director.product", "sabot-director");
        try (ProductProcess p = ProductProcess.start(director, List.of(), List.of(
                "-application", "org.eclipse.equinox.p2.publisher.FeaturesAndBundlesPublisher",
                "-metadataRepository", to.toUri().toString(), "-artifactRepository", to.toUri().toString(),
                "-source", source.toString(), "-publishArtifacts"))) {
            assertEquals(0, p.waitFor(), p.output());
        }
        assertTrue(Files.exists(to.resolve("content.xml")) || Files.exists(to.resolve("content.jar")),
                "the publisher wrote no repository to " + to);
        return new String[] {newFeature, newBundle};
    }

    /** 0.1.0.202611231723 -> 0.1.0.202611231724: the qualifier of a later build. */
    static String bump(String version) {
        Matcher m = Pattern.compile("(\\d+\\.\\d+\\.\\d+\\.)(\\d+)").matcher(version);
        assertTrue(m.matches(), "not a version with a numeric qualifier: " + version);
        return m.group(1) + (Long.parseLong(m.group(2)) + 1);
    }

    private interface Edit {
        String apply(String text);
    }

    /** Copies a jar, editing one text entry (which must change). */
    private static void rewrite(Path from, Path to, String entry, Edit edit) throws IOException {
        boolean edited = false;
        try (ZipInputStream in = new ZipInputStream(Files.newInputStream(from));
                ZipOutputStream out = new ZipOutputStream(Files.newOutputStream(to))) {
            for (ZipEntry e; (e = in.getNextEntry()) != null;) {
                byte[] bytes = in.readAllBytes();
                if (e.getName().equals(entry)) {
                    String before = new String(bytes, StandardCharsets.UTF_8);
                    String after = edit.apply(before);
                    assertFalse(before.equals(after), entry + " of " + from + " unchanged");
                    bytes = after.getBytes(StandardCharsets.UTF_8);
                    edited = true;
                }
                out.putNextEntry(new ZipEntry(e.getName()));
                out.write(bytes);
                out.closeEntry();
            }
        }
        assertTrue(edited, "no " + entry + " in " + from);
    }

    private static Path only(Path folder, String glob) throws IOException {
        List<Path> found = new ArrayList<>();
        try (DirectoryStream<Path> s = Files.newDirectoryStream(folder, glob)) {
            s.forEach(found::add);
        }
        assertEquals(1, found.size(), glob + " in " + folder + ": " + found);
        return found.get(0);
    }

    /** The newest p2 profile of the workbench copy (the director and the p2 UI write a new one per change). */
    private static String profile(Path workbench) throws IOException {
        Path registry = workbench.resolve("p2/org.eclipse.equinox.p2.engine/profileRegistry/DefaultProfile.profile");
        Path newest;
        try (Stream<Path> s = Files.list(registry)) {
            newest = s.filter(p -> p.getFileName().toString().endsWith(".profile.gz")).max((a, b) -> Long.compare(
                    timestamp(a), timestamp(b))).orElseThrow(() -> new AssertionError("no profile in " + registry));
        }
        try (InputStream in = new GZIPInputStream(Files.newInputStream(newest))) {
            ByteArrayOutputStream buf = new ByteArrayOutputStream();
            in.transferTo(buf);
            return buf.toString(StandardCharsets.UTF_8);
        }
    }

    private static long timestamp(Path profile) {
        return Long.parseLong(profile.getFileName().toString().replace(".profile.gz", ""));
    }

    private static String versionIn(String profile, String iu) {
        Matcher m = Pattern.compile("<unit id='" + Pattern.quote(iu) + "' version='([^']+)'").matcher(profile);
        assertTrue(m.find(), iu + " not in the profile");
        return m.group(1);
    }

    private static String bundlesInfo(Path workbench) throws IOException {
        return Files.readString(workbench.resolve("configuration/org.eclipse.equinox.simpleconfigurator/bundles.info"));
    }

    private static int count(String text, String what) {
        return (int) text.lines().filter(l -> l.contains(what)).count();
    }

    private static String line(String text, String prefix) {
        return text.lines().filter(l -> l.contains(prefix)).findFirst().orElseThrow(() -> new AssertionError(
                "no line " + prefix + " in\n" + text));
    }
}
