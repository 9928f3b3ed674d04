package sabot.products;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The workbench's UI plug-ins (joystick, remote files, identity, PID tuning, traffic statistics) install from the built update site into a
 * copy of the materialized workbench with the p2 director, as {@code ./sabot install FEATURE} does; each announces
 * itself at the next start. Uninstalled again, the workbench still starts and closes cleanly without them (plug-ins
 * are optional, the core is not). Starts real workbench windows: needs the X display of ./sabot test (Xvfb).
 */
class UiPluginInstallTest {

    /** Feature id to the line its plug-in logs when it starts. */
    private static final Map<String, String> PLUGINS = Map.of(
            "sabot.workbench.joystick.feature", "Sabot joystick plug-in",
            "sabot.workbench.remotefs.feature", "Sabot remote files plug-in",
            "sabot.workbench.identity.feature", "Sabot identity plug-in",
            "sabot.workbench.pid.feature", "Sabot PID tuning plug-in",
            "sabot.workbench.statistics.feature", "Sabot statistics plug-in");

    @TempDir
    Path dir;

    @Test
    void uiPluginsInstallFromTheUpdateSiteAppearAtTheNextStartAndUninstallLeavingTheCoreWorking() throws Exception {
        assertTrue(System.getenv("DISPLAY") != null, "no X display: run under xvfb-run (./sabot test does)");
        Path workbench = PluginInstallTest.copy(ProductProcess.product("sabot.workbench.product", "sabot-workbench"), dir.resolve(
                "workbench"));
        String bundlesInfo = "configuration/org.eclipse.equinox.simpleconfigurator/bundles.info";

        director("-installIU", ius(), workbench);
        String bundles = Files.readString(workbench.resolve(bundlesInfo));
        for (String b : List.of("sabot.workbench.joystick", "sabot.workbench.remotefs", "sabot.workbench.identity",
                "sabot.workbench.pid", "sabot.workbench.statistics")) {
            assertTrue(bundles.lines().anyMatch(l -> l.startsWith(b + ",") && l.endsWith(",4,true")), b
                    + " not in bundles.info as started:\n" + bundles);
        }
        assertTrue(bundles.lines().anyMatch(l -> l.startsWith("org.eclipse.swtchart,")), "SWTChart not installed");
        String withPlugins = start(workbench);
        for (Map.Entry<String, String> p : PLUGINS.entrySet()) {
            assertTrue(withPlugins.contains(p.getValue() + " "), p.getKey() + " did not start:\n" + withPlugins);
        }

        director("-uninstallIU", ius(), workbench);
        String after = Files.readString(workbench.resolve(bundlesInfo));
        assertFalse(after.contains("sabot.workbench.joystick,") || after.contains("sabot.workbench.pid,"), after);
        assertTrue(after.lines().anyMatch(l -> l.startsWith("sabot.workbench,")), "the core went with them");
        String without = start(workbench);
        for (String line : PLUGINS.values()) {
            assertFalse(without.contains(line), "still there after the uninstall: " + line + "\n" + without);
        }
        // the core still opens its window and closes cleanly (exit 0 checked by start)
        assertTrue(without.contains("Sabot Workbench window open"), without);
    }

    private static String ius() {
        return String.join(",", PLUGINS.keySet().stream().sorted().map(f -> f + ".feature.group").toList());
    }

    private void director(String operation, String ius, Path workbench) throws Exception {
        Path site = ProductProcess.root().resolve("product/sabot.site/target/repository");
        Path director = ProductProcess.product("sabot.director.product", "sabot-director");
        List<String> args = new ArrayList<>(List.of("-application", "org.eclipse.equinox.p2.director", "-repository",
                site.toUri().toString(), operation, ius, "-destination", workbench.toString(), "-profile",
                "DefaultProfile"));
        try (ProductProcess p = ProductProcess.start(director, List.of(), args)) {
            assertEquals(0, p.waitFor(), p.output());
            assertTrue(p.output().contains("Operation completed"), p.output());
        }
    }

    /** Starts the workbench until its window is open, then lets it close; returns its console. */
    private String start(Path workbench) throws Exception {
        try (ProductProcess p = ProductProcess.start(workbench, List.of(), List.of("-data", dir.resolve("workspace")
                .toString(), "-sabot.exit"))) {
            assertEquals(0, p.waitFor(), p.output());
            return p.output();
        }
    }
}
