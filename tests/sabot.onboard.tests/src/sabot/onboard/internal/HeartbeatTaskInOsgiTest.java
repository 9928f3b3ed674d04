package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Hashtable;
import java.util.Map;
import java.util.concurrent.TimeUnit;

import org.junit.jupiter.api.Test;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.cm.Configuration;
import org.osgi.service.cm.ConfigurationAdmin;
import org.osgi.service.component.runtime.ServiceComponentRuntime;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.util.tracker.ServiceTracker;

import sabot.onboard.task.OnboardTask;

/** The task mechanism in a real OSGi runtime: Felix SCR, Equinox Config Admin and Metatype. */
class HeartbeatTaskInOsgiTest {

    private final BundleContext context = FrameworkUtil.getBundle(OnboardApplication.class).getBundleContext();

    @Test
    void catalogListsHeartbeatWithItsDeclaredSettings() throws Exception {
        Map<String, Map<String, SettingSpec>> catalog = OsgiTaskCatalog.read(context,
                service(ServiceComponentRuntime.class), service(MetaTypeService.class));
        Map<String, SettingSpec> heartbeat = catalog.get("heartbeat");
        assertNotNull(heartbeat, "heartbeat task not found in " + catalog.keySet());
        assertEquals(1.0, heartbeat.get("period").min());
        assertEquals(3600.0, heartbeat.get("period").max());
        assertTrue(heartbeat.containsKey("warnLoad"));
    }

    /**
     * A configuration a task wrote for another service (the portal's of Felix HTTP) outlives a killed process: the
     * next start deletes it when its task is not enabled, and keeps it when it is (two tasks with no component, so
     * that nothing activates).
     */
    @Test
    void aStartDeletesWhatDisabledTasksLeftForOtherServices() throws Exception {
        ConfigurationAdmin cm = service(ConfigurationAdmin.class);
        Configuration left = cm.getConfiguration("sabot.test.http", "?");
        Configuration kept = cm.getConfiguration("sabot.test.other", "?");
        left.update(new Hashtable<>(Map.of(OnboardTask.TASK_PROPERTY, "stopped", "port", 8080)));
        kept.update(new Hashtable<>(Map.of(OnboardTask.TASK_PROPERTY, "running")));
        try {
            OnboardApplication.applyTaskConfigurations(cm, java.util.Set.of("running", "stopped"), Map.of(
                    "running", new Hashtable<>(Map.of("robot.name", "r"))));
            assertNull(cm.listConfigurations("(service.pid=sabot.test.http)"), "the disabled task's left-over");
            assertNotNull(cm.listConfigurations("(service.pid=sabot.test.other)"), "the enabled task's");
            assertNotNull(cm.listConfigurations("(service.pid=sabot.task.running)"), "the enabled task's own");
        } finally {
            for (String pid : new String[] { "sabot.test.other", "sabot.task.running", "sabot.test.http" }) {
                Configuration[] c = cm.listConfigurations("(service.pid=" + pid + ")");
                if (c != null) {
                    c[0].delete();
                }
            }
        }
    }

    @Test
    void heartbeatRunsOnlyWhileConfigured() throws Exception {
        ServiceTracker<OnboardTask, OnboardTask> tasks = new ServiceTracker<>(context, OnboardTask.class, null);
        tasks.open();
        try {
            assertNull(tasks.getService(), "a task is active without configuration");
            Configuration config = service(ConfigurationAdmin.class).getConfiguration("sabot.task.heartbeat", "?");
            Hashtable<String, Object> props = new Hashtable<>();
            props.put("period", 1);
            config.update(props);

            OnboardTask task = tasks.waitForService(TimeUnit.SECONDS.toMillis(10));
            assertNotNull(task, "heartbeat did not start once configured");
            assertEquals("heartbeat", task.name());
            assertTrue(task.status().contains("period 1 s"), task.status());

            config.delete();
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
            while (tasks.getService() != null && System.nanoTime() < deadline) {
                Thread.onSpinWait(); // SCR deactivates asynchronously after the configuration is deleted
            }
            assertNull(tasks.getService(), "heartbeat still active after its configuration was deleted");
        } finally {
            tasks.close();
        }
    }

    private <S> S service(Class<S> type) throws InterruptedException {
        ServiceTracker<S, S> t = new ServiceTracker<>(context, type, null);
        t.open();
        S s = t.waitForService(10_000);
        assertNotNull(s, type.getSimpleName() + " not available");
        return s;
    }
}
