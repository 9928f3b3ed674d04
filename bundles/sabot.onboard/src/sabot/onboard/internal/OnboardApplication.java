package sabot.onboard.internal;

import java.io.IOException;
import java.lang.reflect.InvocationTargetException;
import java.net.URI;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.Hashtable;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.eclipse.equinox.app.IApplication;
import org.eclipse.equinox.app.IApplicationContext;
import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.InvalidSyntaxException;
import org.osgi.framework.ServiceReference;
import org.osgi.service.cm.Configuration;
import org.osgi.service.cm.ConfigurationAdmin;
import org.osgi.service.component.runtime.ServiceComponentRuntime;
import org.osgi.service.component.runtime.dto.ComponentDescriptionDTO;
import org.osgi.service.metatype.MetaTypeService;
import org.osgi.util.tracker.ServiceTracker;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;
import org.slf4j.bridge.SLF4JBridgeHandler;

import sabot.onboard.config.OnboardSettings;
import sabot.onboard.task.OnboardTask;
import sabot.onboard.task.TaskSettingsCheck;

/**
 * The robot's headless application: reads the configuration file, starts the tasks it enables, runs until SIGTERM
 * (or SIGINT, or {@link #stop()}), then stops the tasks and exits with status 0.
 * <p>
 * Exit statuses: 0 after a clean stop; 2 for a configuration error (one log line naming the file, line and key);
 * 3 when an enabled task did not start.
 */
public final class OnboardApplication implements IApplication {

    /** Exit status for an invalid configuration file. */
    public static final Integer EXIT_CONFIG_ERROR = 2;
    /** Exit status when an enabled task fails to start. */
    public static final Integer EXIT_TASK_FAILED = 3;
    /** System property naming the configuration file (the {@code -config FILE} argument wins). */
    public static final String CONFIG_PROPERTY = "sabot.onboard.config";

    private static final Logger LOG = LoggerFactory.getLogger("sabot.onboard");
    private static final long TASK_START_TIMEOUT_S = 20;
    private static final long SERVICE_TIMEOUT_S = 20;

    private final CountDownLatch stopRequested = new CountDownLatch(1);

    @Override
    public Object start(IApplicationContext context) throws Exception {
        // Smack logs through java.util.logging: into SLF4J, so that etc/logback.xml governs its lines too
        SLF4JBridgeHandler.removeHandlersForRootLogger();
        SLF4JBridgeHandler.install();
        Bundle bundle = FrameworkUtil.getBundle(getClass());
        BundleContext bc = bundle.getBundleContext();
        String version = bundle.getVersion().toString();
        String[] args = (String[]) context.getArguments().getOrDefault(IApplicationContext.APPLICATION_ARGS,
                new String[0]);
        Path file = configFile(args);
        LOG.info("Sabot Onboard {} starting (Java {}), configuration {}", version, Runtime.version(), file);

        ServiceComponentRuntime scr = await(bc, ServiceComponentRuntime.class);
        MetaTypeService metaType = await(bc, MetaTypeService.class);
        ConfigurationAdmin configAdmin = await(bc, ConfigurationAdmin.class);
        if (scr == null || metaType == null || configAdmin == null) {
            LOG.error("the OSGi runtime is incomplete: Declarative Services, Metatype or Config Admin is missing");
            return EXIT_TASK_FAILED;
        }

        Map<String, Map<String, SettingSpec>> catalog = OsgiTaskCatalog.read(bc, scr, metaType);
        OnboardConfigFile config;
        Map<String, Hashtable<String, Object>> enabled;
        try {
            config = OnboardConfigFile.read(file);
            enabled = TaskSettings.resolve(config, catalog);
            TaskSettings.check(config, enabled, task -> settingsChecks(bc, task));
        } catch (ConfigError e) {
            LOG.error("configuration error: {}", e.getMessage());
            return EXIT_CONFIG_ERROR;
        }
        String robot = config.robotName("unnamed");
        enabled.values().forEach(settings -> settings.put(OnboardTask.ROBOT_NAME, robot));
        installSignalHandlers();
        context.applicationRunning();

        Set<String> running = ConcurrentHashMap.newKeySet();
        List<ServiceReference<OnboardTask>> retried = new ArrayList<>();
        Object progress = new Object();
        ServiceTracker<OnboardTask, OnboardTask> tracker = new ServiceTracker<>(bc, OnboardTask.class, null) {
            @Override
            public OnboardTask addingService(ServiceReference<OnboardTask> reference) {
                OnboardTask task = super.addingService(reference);
                if (task == null) {
                    // its component failed to activate (the error is above, e.g. a board that did not answer in
                    // time on a loaded machine): taken again by retryUntracked, each second until the start timeout
                    LOG.warn("task {} registered but not activated; trying again", reference.getProperty(
                            "component.name"));
                    return null;
                }
                synchronized (progress) {
                    running.add(task.name());
                    progress.notifyAll();
                }
                return task;
            }

            @Override
            public void removedService(ServiceReference<OnboardTask> reference, OnboardTask task) {
                synchronized (progress) {
                    running.remove(task.name());
                    progress.notifyAll();
                }
                super.removedService(reference, task);
            }
        };
        tracker.open();
        // the file as a service (the robot's web page shows and changes it): the same catalogue, checks and texts
        org.osgi.framework.ServiceRegistration<OnboardSettings> settingsService = bc.registerService(
                OnboardSettings.class, new ConfigEditor(file, robot, catalog, () -> OsgiTaskCatalog.forms(bc, scr,
                        metaType), task -> settingsChecks(bc, task), (task, properties) -> configAdmin
                                .getConfiguration(OnboardTask.PID_PREFIX + task, "?").update(properties)), null);
        try {
            applyTaskConfigurations(configAdmin, catalog.keySet(), enabled);
            List<String> missing = awaitTasks(enabled.keySet(), running, progress, () -> retryUntracked(bc,
                    tracker, retried, running, progress));
            if (!missing.isEmpty()) {
                LOG.error("task(s) {} did not start within {} s; see the errors above", missing,
                        TASK_START_TIMEOUT_S);
                return EXIT_TASK_FAILED;
            }
            LOG.info("Sabot Onboard {} running as '{}': {} task(s) loaded: {}", version, robot, enabled.size(),
                    enabled.isEmpty() ? "none" : String.join(", ", enabled.keySet()));
            stopRequested.await();
            LOG.info("Sabot Onboard stopping");
            return IApplication.EXIT_OK;
        } finally {
            settingsService.unregister();
            stopTasks(scr, enabled.keySet());
            for (String task : enabled.keySet()) {
                deleteConfiguration(configAdmin, "(" + org.osgi.framework.Constants.SERVICE_PID + "="
                        + OnboardTask.PID_PREFIX + task + ")");
            }
            tracker.close();
            for (ServiceReference<OnboardTask> r : retried) {
                bc.ungetService(r);
            }
            LOG.info("Sabot Onboard stopped");
        }
    }

    /**
     * Gets each registered task the tracker does not hold (its activation failed when the tracker asked): SCR
     * activates it again, and a task that now starts counts as running. The service stays got until the end.
     */
    private static void retryUntracked(BundleContext bc, ServiceTracker<OnboardTask, OnboardTask> tracker,
            List<ServiceReference<OnboardTask>> retried, Set<String> running, Object progress) {
        try {
            Set<ServiceReference<OnboardTask>> tracked = tracker.getTracked().keySet();
            for (ServiceReference<OnboardTask> r : bc.getServiceReferences(OnboardTask.class, null)) {
                if (tracked.contains(r) || retried.contains(r)) {
                    continue;
                }
                OnboardTask task = bc.getService(r);
                if (task != null) {
                    retried.add(r);
                    LOG.info("task {} activated on a second attempt", task.name());
                    synchronized (progress) {
                        running.add(task.name());
                    }
                }
            }
        } catch (InvalidSyntaxException e) {
            throw new IllegalStateException(e); // no filter
        }
    }

    /** @return the {@link TaskSettingsCheck} services registered for a task (see its {@link TaskSettingsCheck#TASK}) */
    static List<TaskSettingsCheck> settingsChecks(BundleContext bc, String task) {
        List<TaskSettingsCheck> checks = new ArrayList<>();
        try {
            for (ServiceReference<TaskSettingsCheck> ref : bc.getServiceReferences(TaskSettingsCheck.class, "("
                    + TaskSettingsCheck.TASK + "=" + task + ")")) {
                TaskSettingsCheck check = bc.getService(ref);
                if (check != null) {
                    checks.add(check); // (released when the framework stops: the checks are stateless services)
                }
            }
        } catch (org.osgi.framework.InvalidSyntaxException e) {
            throw new IllegalArgumentException("task name '" + task + "' in a filter", e); // names are [a-z0-9_-]
        }
        return checks;
    }

    @Override
    public void stop() {
        stopRequested.countDown();
    }

    /** The file named by {@code -config FILE}, else the system property, else etc/onboard.conf of the install. */
    static Path configFile(String[] args) {
        for (int i = 0; i < args.length - 1; i++) {
            if (args[i].equals("-config") || args[i].equals("--config")) {
                return Paths.get(args[i + 1]).toAbsolutePath();
            }
        }
        String property = System.getProperty(CONFIG_PROPERTY);
        if (property != null && !property.isBlank()) {
            return Paths.get(property).toAbsolutePath();
        }
        String home = System.getProperty("eclipse.home.location");
        Path base = home != null && home.startsWith("file:") ? Paths.get(URI.create(home.replace(" ", "%20")))
                : Paths.get("");
        return base.resolve("etc/onboard.conf").toAbsolutePath();
    }

    /**
     * Enabled tasks get their configuration (DS then activates them); installed but disabled tasks lose any
     * configuration left from an earlier run (Config Admin persists configurations across restarts).
     */
    static void applyTaskConfigurations(ConfigurationAdmin configAdmin, Set<String> installed,
            Map<String, Hashtable<String, Object>> enabled) throws IOException {
        for (String task : installed) {
            String pid = OnboardTask.PID_PREFIX + task;
            if (enabled.containsKey(task)) {
                configAdmin.getConfiguration(pid, "?").update(enabled.get(task));
            } else {
                deleteConfiguration(configAdmin, "(" + org.osgi.framework.Constants.SERVICE_PID + "=" + pid + ")");
                deleteConfiguration(configAdmin, "(" + OnboardTask.TASK_PROPERTY + "=" + task + ")");
            }
        }
    }

    /** Deletes the configurations that {@code filter} selects. */
    private static void deleteConfiguration(ConfigurationAdmin configAdmin, String filter) {
        try {
            Configuration[] existing = configAdmin.listConfigurations(filter);
            if (existing != null) {
                for (Configuration c : existing) {
                    c.delete();
                }
            }
        } catch (IOException | org.osgi.framework.InvalidSyntaxException e) {
            LOG.warn("could not delete the configurations {}: {}", filter, e.toString());
        }
    }

    private static List<String> awaitTasks(Set<String> expected, Set<String> running, Object progress,
            Runnable retry) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TASK_START_TIMEOUT_S);
        while (true) {
            synchronized (progress) {
                long left = deadline - System.nanoTime();
                if (running.containsAll(expected) || left <= 0) {
                    break;
                }
                TimeUnit.NANOSECONDS.timedWait(progress, Math.min(left, TimeUnit.SECONDS.toNanos(1)));
            }
            if (!running.containsAll(expected)) {
                retry.run();
            }
        }
        List<String> missing = new ArrayList<>(expected);
        missing.removeAll(running);
        return missing;
    }

    /**
     * Disables the tasks' components and waits until SCR has deactivated them (the promise resolves after their
     * deactivate methods returned), so "stopped" is logged only when every task has stopped.
     */
    private static void stopTasks(ServiceComponentRuntime scr, Set<String> tasks) {
        for (ComponentDescriptionDTO component : scr.getComponentDescriptionDTOs()) {
            if (!component.name.startsWith(OnboardTask.PID_PREFIX)
                    || !tasks.contains(component.name.substring(OnboardTask.PID_PREFIX.length()))) {
                continue;
            }
            try {
                scr.disableComponent(component).timeout(TimeUnit.SECONDS.toMillis(TASK_START_TIMEOUT_S)).getValue();
            } catch (InvocationTargetException e) {
                LOG.warn("task {} did not stop cleanly: {}", component.name, e.getCause().toString());
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
        }
    }

    private static <S> S await(BundleContext bc, Class<S> type) throws InterruptedException {
        ServiceTracker<S, S> t = new ServiceTracker<>(bc, type, null);
        t.open();
        try {
            return t.waitForService(TimeUnit.SECONDS.toMillis(SERVICE_TIMEOUT_S));
        } finally {
            t.close();
        }
    }

    /**
     * SIGTERM (service managers, {@code kill}) and SIGINT (Ctrl-C) request an orderly stop instead of the JVM's
     * default of running shutdown hooks and exiting with 143/130: tasks are deactivated, then the launcher exits 0.
     */
    @SuppressWarnings("restriction")
    private void installSignalHandlers() {
        for (String name : new String[] { "TERM", "INT" }) {
            try {
                sun.misc.Signal.handle(new sun.misc.Signal(name), signal -> {
                    LOG.info("received SIG{}", signal.getName());
                    stop();
                });
            } catch (IllegalArgumentException unsupported) {
                LOG.warn("cannot handle SIG{} on this platform: {}", name, unsupported.getMessage());
            }
        }
    }
}
