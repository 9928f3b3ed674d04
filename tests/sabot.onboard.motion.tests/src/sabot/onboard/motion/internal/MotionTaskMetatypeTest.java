package sabot.onboard.motion.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;

import org.eclipse.equinox.metatype.EquinoxAttributeDefinition;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;
import org.osgi.framework.Bundle;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.component.runtime.ServiceComponentRuntime;
import org.osgi.service.component.runtime.dto.ComponentDescriptionDTO;
import org.osgi.service.metatype.AttributeDefinition;
import org.osgi.util.tracker.ServiceTracker;

import sabot.modbus.Parity;
import sabot.planner.Planners;
import sabot.testsupport.osgi.TaskMetatype;

/**
 * The motion tasks' Metatype descriptions, generated at build time from their {@code @ObjectClassDefinition}
 * annotations into this bundle, read through the real Metatype service (the onboard application checks the
 * configuration file against them): every task has one, its options are the code's names, and its bounds are those
 * the code relies on.
 */
class MotionTaskMetatypeTest {

    private static final List<String> TASKS = List.of("bus", "localizer", "motion", "planner", "teleop", "tracker");
    private static final Map<String, Map<String, AttributeDefinition>> settings = new TreeMap<>();
    private static final List<String> components = new ArrayList<>();

    @BeforeAll
    static void readDescriptions() throws InterruptedException {
        Bundle bundle = FrameworkUtil.getBundle(MotionTask.class);
        ServiceTracker<ServiceComponentRuntime, ServiceComponentRuntime> scr = new ServiceTracker<>(
                bundle.getBundleContext(), ServiceComponentRuntime.class, null);
        scr.open();
        try {
            ServiceComponentRuntime runtime = scr.waitForService(10_000);
            assertNotNull(runtime, "ServiceComponentRuntime not available");
            for (ComponentDescriptionDTO d : runtime.getComponentDescriptionDTOs(bundle)) {
                components.add(d.name);
            }
        } finally {
            scr.close();
        }
        for (String task : TASKS) {
            settings.put(task, TaskMetatype.attributes(bundle, "sabot.task." + task));
        }
    }

    @Test
    void everyMotionTaskHasItsGeneratedDescription() {
        assertEquals(TASKS, List.copyOf(settings.keySet()));
        assertEquals(13, settings.get("localizer").size());
        assertEquals(11, settings.get("tracker").size());
    }

    /** cm.tasks names each task's bundle by the bundle that registered its service: this one, for every motion task. */
    @Test
    void everyMotionTaskIsAComponentOfThisBundle() {
        assertEquals(TASKS.stream().map(t -> "sabot.task." + t).toList(), components.stream().filter(
                c -> c.startsWith("sabot.task.")).sorted().toList());
    }

    @Test
    void optionsAreTheCodesNames() {
        assertEquals(Planners.NAMES, Arrays.asList(settings.get("planner").get("algorithm").getOptionValues()));
        assertEquals(Arrays.stream(Parity.values()).map(Enum::name).sorted().toList(),
                Arrays.stream(settings.get("bus").get("parity").getOptionValues()).sorted().toList());
        assertEquals(List.of(TrackerTask.DFL, TrackerTask.PSEUDOINVERSE),
                Arrays.asList(settings.get("tracker").get("controller").getOptionValues()));
    }

    @Test
    void theMapIsTheOnlySettingWithoutDefault() {
        assertNull(settings.get("planner").get("map").getDefaultValue());
        settings.forEach((task, ads) -> ads.values().stream().filter(ad -> !ad.getID().equals("map")).forEach(
                ad -> assertNotNull(ad.getDefaultValue(), task + "." + ad.getID() + " has no default")));
    }

    @ParameterizedTest(name = "{0}.{1} in [{2}, {3}]")
    @CsvSource({ "motion, rate, 5, 200", "motion, realtimePriority, 0, 99",
        "bus, tcpPort, 1, 65535", "bus, interFrameDelay, 0, 1000", "localizer, startTheta, -3.1416, 3.1416",
        "planner, threads, 1, 2", "teleop, timeout, 0.05, 10", "tracker, speedHeadroom, 0.1, 1" })
    void boundsAreThoseTheCodeReliesOn(String task, String id, String min, String max) {
        EquinoxAttributeDefinition ad = (EquinoxAttributeDefinition) settings.get(task).get(id);
        assertNotNull(ad, task + "." + id);
        assertEquals(Double.parseDouble(min), Double.parseDouble(ad.getMin()), task + "." + id + " minimum");
        assertEquals(Double.parseDouble(max), Double.parseDouble(ad.getMax()), task + "." + id + " maximum");
    }
}
