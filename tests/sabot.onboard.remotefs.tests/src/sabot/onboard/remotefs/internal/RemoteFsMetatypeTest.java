package sabot.onboard.remotefs.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import java.util.Map;

import org.junit.jupiter.api.Test;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;

import sabot.onboard.task.TaskSettingsCheck;
import sabot.testsupport.osgi.TaskMetatype;

/**
 * The Metatype description of the remotefs task, generated from its annotations, says what the code that reads its
 * configuration does: one truth for defaults.
 */
class RemoteFsMetatypeTest {

    private final BundleContext context = FrameworkUtil.getBundle(RemoteFsTask.class).getBundleContext();

    Map<String, String> defaults(String pid) throws Exception {
        return TaskMetatype.defaults(context.getBundle(), pid);
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
    void settingsCheckIsRegistered() throws Exception {
        var refs = context.getServiceReferences(TaskSettingsCheck.class, "(" + TaskSettingsCheck.TASK + "=remotefs)");
        assertEquals(1, refs.size());
        List<TaskSettingsCheck.Problem> problems = context.getService(refs.iterator().next()).check(Map.of());
        assertTrue(!problems.isEmpty(), "a missing mandatory setting is a problem");
    }
}
