package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.metatype.MetaTypeInformation;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.util.tracker.ServiceTracker;

import sabot.onboard.task.OnboardTask;
import sabot.testsupport.osgi.TaskMetatype;

/**
 * The shipped {@code etc/onboard.conf} lists every setting of every task (most commented out), with the default its task's
 * Metatype declares (the tasks' annotations are the one source; the file is their copy for the reader): a setting
 * added to a task without its line in the file, or a default changed in the code and not in the file, fails here.
 * Settings without a default (required) show an example value instead. The test runtime holds every task bundle.
 */
class ShippedConfigurationTest {

    /** The product's configuration file, in the onboard feature's root files. */
    private static final Path SHIPPED = Path.of(System.getProperty("sabot.root", "../.."))
            .resolve("features/sabot.onboard.feature/rootfiles/etc/onboard.conf");
    /** {@code #task.setting = value   # comment}: a setting, commented out or not ({@code robot.name} is no task's). */
    private static final Pattern SETTING = Pattern.compile("^#?([a-z]+)\\.([A-Za-z]+) =\\s*([^#\\s]*)\\s*(?:#.*)?$");

    /** task → setting → default (null: none), from the running Metatype service. */
    private static final Map<String, Map<String, String>> declared = new TreeMap<>();

    @BeforeAll
    static void readDescriptions() throws InterruptedException {
        BundleContext context = FrameworkUtil.getBundle(OnboardApplication.class).getBundleContext();
        ServiceTracker<MetaTypeService, MetaTypeService> t = new ServiceTracker<>(context, MetaTypeService.class,
                null);
        t.open();
        try {
            MetaTypeService metaType = t.waitForService(10_000);
            assertNotNull(metaType, "no MetaTypeService");
            for (Bundle b : context.getBundles()) {
                MetaTypeInformation info = metaType.getMetaTypeInformation(b);
                for (String pid : info == null ? new String[0] : info.getPids()) {
                    if (pid.startsWith(OnboardTask.PID_PREFIX)) {
                        declared.put(pid.substring(OnboardTask.PID_PREFIX.length()), TaskMetatype.defaults(b, pid));
                    }
                }
            }
        } finally {
            t.close();
        }
    }

    @Test
    void theRuntimeHoldsEveryTaskBundle() {
        assertEquals(List.of("bus", "controlml", "heartbeat", "localizer", "motion", "peers", "planner", "portal", "remotefs",
                "teleop", "tracker"), List.copyOf(declared.keySet()));
    }

    @Test
    void theShippedFileListsEverySettingOnceWithItsTasksDefault() throws IOException {
        Map<String, Map<String, String>> listed = new TreeMap<>();
        List<String> problems = new ArrayList<>();
        int n = 0;
        for (String line : Files.readAllLines(SHIPPED)) {
            n++;
            Matcher m = SETTING.matcher(line);
            if (!m.matches() || m.group(1).equals("robot")) {
                continue;
            }
            String task = m.group(1);
            String setting = m.group(2);
            String value = m.group(3);
            Map<String, String> settings = declared.get(task);
            if (settings == null || !settings.containsKey(setting)) {
                problems.add("line " + n + ": " + task + "." + setting + " is no setting of a task");
                continue;
            }
            if (listed.computeIfAbsent(task, k -> new TreeMap<>()).put(setting, value) != null) {
                problems.add("line " + n + ": " + task + "." + setting + " listed twice");
            }
            String declaredDefault = settings.get(setting);
            if (declaredDefault != null && !sameValue(declaredDefault, value)) {
                problems.add("line " + n + ": " + task + "." + setting + " = " + value + ", but its default is "
                        + declaredDefault);
            }
        }
        declared.forEach((task, settings) -> settings.keySet().forEach(setting -> {
            if (!listed.getOrDefault(task, Map.of()).containsKey(setting)) {
                problems.add(task + "." + setting + " is not listed");
            }
        }));
        assertTrue(problems.isEmpty(), SHIPPED + ":\n" + String.join("\n", problems));
    }

    /** Numbers compare by value (50 = 50.0), everything else as text (an empty default is an empty value). */
    private static boolean sameValue(String declaredDefault, String value) {
        try {
            return Double.parseDouble(declaredDefault) == Double.parseDouble(value);
        } catch (NumberFormatException e) {
            return declaredDefault.equals(value);
        }
    }
}
