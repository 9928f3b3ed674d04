package sabot.onboard.internal.session;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeSet;

import org.junit.jupiter.api.Test;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.metatype.AttributeDefinition;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.service.metatype.ObjectClassDefinition;
import org.osgi.util.tracker.ServiceTracker;

import sabot.controlml.StaleCommandPolicy;
import sabot.onboard.internal.OnboardApplication;
import sabot.onboard.internal.remotefs.RemoteFsLimits;
import sabot.onboard.task.TaskSettingsCheck;

/**
 * The Metatype descriptions of the controlml and remotefs tasks, generated from their annotations, say what the code
 * that reads their configuration does: one truth for defaults.
 */
class TaskMetatypeTest {

    private final BundleContext context = FrameworkUtil.getBundle(OnboardApplication.class).getBundleContext();

    Map<String, String> defaults(String pid) throws Exception {
        ServiceTracker<MetaTypeService, MetaTypeService> t = new ServiceTracker<>(context, MetaTypeService.class,
                null);
        t.open();
        try {
            MetaTypeService metaType = t.waitForService(10_000);
            assertNotNull(metaType);
            ObjectClassDefinition ocd = metaType.getMetaTypeInformation(context.getBundle()).getObjectClassDefinition(
                    pid, null);
            Map<String, String> d = new HashMap<>();
            for (AttributeDefinition ad : ocd.getAttributeDefinitions(ObjectClassDefinition.ALL)) {
                String[] v = ad.getDefaultValue();
                d.put(ad.getID(), v == null || v.length == 0 ? null : v[0]);
            }
            return d;
        } finally {
            t.close();
        }
    }

    @Test
    void controlmlDeclaresExactlyItsSettingsWithTheSessionsDefaults() throws Exception {
        Map<String, String> d = defaults("sabot.task.controlml");
        assertEquals(new TreeSet<>(Set.of("server", "port", "jid", "passwordFile", "resource", "reconnectMin",
                "reconnectMax", "operators", "staleCommandAfter", "positionRate", "velocityRate", "missionRate",
                "obstaclesRate")), new TreeSet<>(d.keySet()));
        assertEquals(ControlMlSettings.DEFAULT_SERVER, d.get("server"));
        assertEquals(ControlMlSettings.DEFAULT_PORT, Integer.parseInt(d.get("port")));
        assertEquals(ControlMlSettings.DEFAULT_RESOURCE, d.get("resource"));
        assertEquals(ControlMlSettings.DEFAULT_RECONNECT_MIN_S, Double.parseDouble(d.get("reconnectMin")));
        assertEquals(ControlMlSettings.DEFAULT_RECONNECT_MAX_S, Double.parseDouble(d.get("reconnectMax")));
        assertEquals(ControlMlSettings.DEFAULT_STALE_COMMAND_AFTER_S, Double.parseDouble(d.get("staleCommandAfter")));
        // the annotation needs a constant; the controlml bundle's default policy is the other copy
        assertEquals(StaleCommandPolicy.DEFAULT.maxAge(), Duration.ofMillis(Math.round(
                ControlMlSettings.DEFAULT_STALE_COMMAND_AFTER_S * 1000)));
    }

    @Test
    void remotefsDefaultsAreRemoteFsLimitsDefault() throws Exception {
        Map<String, String> d = defaults("sabot.task.remotefs");
        RemoteFsLimits l = RemoteFsLimits.DEFAULT;
        assertEquals(l.maxChunk(), Integer.parseInt(d.get("maxChunk")));
        assertEquals(l.maxFileSize(), Long.parseLong(d.get("maxFileSize")));
        assertEquals(l.maxListPage(), Integer.parseInt(d.get("pageSize")));
        assertEquals(l.maxOpenTransfers(), Integer.parseInt(d.get("maxTransfers")));
        assertEquals(l.readOnly(), Boolean.parseBoolean(d.get("readOnly")));
    }

    @Test
    void settingsChecksAreRegisteredForBothTasks() throws Exception {
        for (String task : List.of("controlml", "remotefs")) {
            var refs = context.getServiceReferences(TaskSettingsCheck.class, "(" + TaskSettingsCheck.TASK + "="
                    + task + ")");
            assertEquals(1, refs.size(), task);
            List<TaskSettingsCheck.Problem> problems = context.getService(refs.iterator().next()).check(Map.of());
            assertTrue(!problems.isEmpty(), task + ": a missing mandatory setting is a problem");
        }
    }
}
