package sabot.onboard.controlml.internal.session;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeSet;

import org.junit.jupiter.api.Test;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;

import sabot.controlml.StaleCommandPolicy;
import sabot.fleet.AccessRules;
import sabot.onboard.task.TaskSettingsCheck;
import sabot.testsupport.osgi.TaskMetatype;

/**
 * The Metatype description of the controlml task, generated from its annotations, says what the code that reads its
 * configuration does: one truth for defaults.
 */
class ControlMlMetatypeTest {

    private final BundleContext context = FrameworkUtil.getBundle(ControlMlSession.class).getBundleContext();

    Map<String, String> defaults(String pid) throws Exception {
        return TaskMetatype.defaults(context.getBundle(), pid);
    }

    @Test
    void controlmlDeclaresExactlyItsSettingsWithTheSessionsDefaults() throws Exception {
        Map<String, String> d = defaults("sabot.task.controlml");
        assertEquals(new TreeSet<>(Set.of("server", "port", "caFile", "jid", "passwordFile", "resource", "reconnectMin",
                "reconnectMax", "observerGroups", "operatorGroups", "maintainerGroups", "openPolicy",
                "staleCommandAfter", "liveness", "positionRate", "velocityRate", "missionRate", "obstaclesRate",
                "batteryRate", "passageRate", "baseRate", "leaseMax", "lobby")),
                new TreeSet<>(d.keySet()));
        // deny by default: the lab's group of each role (the server grants them), no open policy; the lab's robots
        // observe one another (they follow each other's positions, and cannot command)
        assertEquals(AccessRules.OBSERVERS_GROUP + "," + AccessRules.ROBOTS_GROUP, d.get("observerGroups"));
        assertEquals(AccessRules.OPERATORS_GROUP, d.get("operatorGroups"));
        assertEquals(AccessRules.MAINTAINERS_GROUP, d.get("maintainerGroups"));
        assertEquals("false", d.get("openPolicy"));
        assertEquals(ControlMlSettings.DEFAULT_SERVER, d.get("server"));
        assertEquals("", d.get("caFile"), "the JVM's default trust store unless a lab CA is given");
        assertEquals(ControlMlSettings.DEFAULT_PORT, Integer.parseInt(d.get("port")));
        assertEquals(ControlMlSettings.DEFAULT_RESOURCE, d.get("resource"));
        assertEquals(ControlMlSettings.DEFAULT_RECONNECT_MIN_S, Double.parseDouble(d.get("reconnectMin")));
        assertEquals(ControlMlSettings.DEFAULT_RECONNECT_MAX_S, Double.parseDouble(d.get("reconnectMax")));
        assertEquals(ControlMlSettings.DEFAULT_STALE_COMMAND_AFTER_S, Double.parseDouble(d.get("staleCommandAfter")));
        assertEquals(ControlMlSettings.DEFAULT_LIVENESS_S, Double.parseDouble(d.get("liveness")));
        assertEquals(ControlMlSettings.DEFAULT_BASE_RATE_HZ, Double.parseDouble(d.get("baseRate")));
        assertEquals(ControlMlSettings.DEFAULT_LEASE_MAX_S, Double.parseDouble(d.get("leaseMax")));
        assertEquals("", d.get("lobby"), "no fleet lobby unless one is configured");
        // the annotation needs a constant; the controlml bundle's default policy is the other copy
        assertEquals(StaleCommandPolicy.DEFAULT.maxAge(), Duration.ofMillis(Math.round(
                ControlMlSettings.DEFAULT_STALE_COMMAND_AFTER_S * 1000)));
    }

    @Test
    void settingsCheckIsRegistered() throws Exception {
        var refs = context.getServiceReferences(TaskSettingsCheck.class, "(" + TaskSettingsCheck.TASK + "=controlml)");
        assertEquals(1, refs.size());
        List<TaskSettingsCheck.Problem> problems = context.getService(refs.iterator().next()).check(Map.of());
        assertTrue(!problems.isEmpty(), "a missing mandatory setting is a problem");
    }
}
