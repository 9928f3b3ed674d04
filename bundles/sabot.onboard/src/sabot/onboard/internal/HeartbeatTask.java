package sabot.onboard.internal;

import java.lang.management.ManagementFactory;
import java.lang.management.MemoryUsage;
import java.time.Duration;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.onboard.task.NamedThreads;
import sabot.onboard.task.OnboardTask;

/**
 * Diagnostic task: logs the process's uptime, the system load, heap and thread count every {@code period} seconds,
 * as a warning when the load per CPU exceeds {@code warnLoad}. Settings: {@link Config}.
 */
@Designate(ocd = HeartbeatTask.Config.class, factory = false)
@Component(name = "sabot.task.heartbeat", configurationPolicy = ConfigurationPolicy.REQUIRE, service = OnboardTask.class)
public final class HeartbeatTask implements OnboardTask {

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = "sabot.task.heartbeat", name = "Heartbeat task",
            description = "Logs uptime, system load, heap and thread count at a fixed period.")
    public @interface Config {
        @AttributeDefinition(name = "Period", description = "Seconds between two heartbeat log lines.", min = "1",
                max = "3600")
        int period() default 10;

        @AttributeDefinition(name = "Load warning", min = "0", max = "1",
                description = "System load average per CPU above which a heartbeat is logged as a warning.")
        double warnLoad() default 0.9;
    }

    private static final Logger LOG = LoggerFactory.getLogger(HeartbeatTask.class);
    private static final long MIB = 1024 * 1024;

    private final AtomicLong beats = new AtomicLong();
    private ScheduledExecutorService timer;
    private Config config;

    @Activate
    void activate(Config config) {
        this.config = config;
        timer = Executors.newSingleThreadScheduledExecutor(NamedThreads.daemon("sabot-heartbeat"));
        timer.scheduleAtFixedRate(this::beat, 0, config.period(), TimeUnit.SECONDS);
        LOG.info("heartbeat task started: period {} s", config.period());
    }

    @Deactivate
    void deactivate() {
        timer.shutdownNow();
        LOG.info("heartbeat task stopped after {} beats", beats.get());
    }

    private void beat() {
        long n = beats.incrementAndGet();
        Duration uptime = Duration.ofMillis(ManagementFactory.getRuntimeMXBean().getUptime());
        int cpus = Runtime.getRuntime().availableProcessors();
        double load = ManagementFactory.getOperatingSystemMXBean().getSystemLoadAverage();
        MemoryUsage heap = ManagementFactory.getMemoryMXBean().getHeapMemoryUsage();
        int threads = ManagementFactory.getThreadMXBean().getThreadCount();
        String line = String.format("heartbeat #%d: uptime %s, load %.2f (%d CPUs), heap %d/%d MiB, %d threads", n,
                format(uptime), load, cpus, heap.getUsed() / MIB, heap.getMax() / MIB, threads);
        if (load >= 0 && load / cpus > config.warnLoad()) {
            LOG.warn("{} - load per CPU above {}", line, config.warnLoad());
        } else {
            LOG.info(line);
        }
    }

    private static String format(Duration d) {
        return String.format("%d:%02d:%02d", d.toHours(), d.toMinutesPart(), d.toSecondsPart());
    }

    @Override
    public String name() {
        return "heartbeat";
    }

    @Override
    public String status() {
        return "running, " + beats.get() + " beats, period " + config.period() + " s";
    }
}
