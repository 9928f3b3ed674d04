package sabot.onboard.internal.motion;

import java.io.IOException;
import java.time.Duration;
import java.util.Dictionary;
import java.util.Hashtable;
import java.util.Locale;

import org.osgi.framework.BundleContext;
import org.osgi.framework.ServiceRegistration;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.modbus.BusSettings;
import sabot.modbus.InsClient;
import sabot.modbus.ModbusBus;
import sabot.modbus.ModbusBuses;
import sabot.modbus.Parity;
import sabot.modbus.SactClient;
import sabot.modbus.LandmarkClient;
import sabot.modbus.SonarClient;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code bus}: the robot's RS-485 line (Modbus RTU master on a serial device, or RTU framing over TCP) and the
 * board clients on it, registered as services ({@link SactClient}, {@link InsClient}, {@link SonarClient},
 * {@link LandmarkClient}: the landmark board is optional) and as the control loop's {@link RobotBoards}. Settings:
 * OSGI-INF/metatype/bus.xml.
 */
@Component(name = "sabot.task.bus", configurationPolicy = ConfigurationPolicy.REQUIRE, service = OnboardTask.class)
public final class BusTask implements OnboardTask {

    /** Settings (names match the Metatype description). */
    public @interface Config {
        /** @return serial device, e.g. /dev/ttyUSB0 (empty when tcpHost is set) */
        String port() default "";

        /** @return host of an RTU-over-TCP gateway (empty for a serial line) */
        String tcpHost() default "";

        /** @return TCP port of the gateway */
        int tcpPort() default 502;

        /** @return baud rate, bit/s */
        int baud() default 115200;

        /** @return parity: EVEN (the SACT bus), NONE (a pseudo-terminal refuses parity), ODD */
        String parity() default "EVEN";

        /** @return ms to wait for an answer */
        int responseTimeout() default 50;

        /** @return retries after a timeout or a corrupt answer */
        int retries() default 1;

        /** @return ms of silence between frames (t3.5 at 115200 baud is 1.75 ms) */
        double interFrameDelay() default 1.75;

        /** @return ms without a good answer after which a board is faulted (the robot stops) */
        int faultAfter() default 200;
    }

    private static final Logger LOG = LoggerFactory.getLogger("sabot.bus");

    private ModbusBus bus;
    private Config config;
    private ServiceRegistration<?> boards;
    private ServiceRegistration<?> sact;
    private ServiceRegistration<?> ins;
    private ServiceRegistration<?> sonar;
    private ServiceRegistration<?> landmark;

    @Activate
    void activate(Config c, BundleContext context) throws IOException {
        this.config = c;
        BusSettings base = c.tcpHost().isBlank() ? BusSettings.serial(c.port()) : BusSettings.tcp(c.tcpHost(),
                c.tcpPort());
        BusSettings settings = base.withBaud(c.baud()).withParity(Parity.valueOf(c.parity().toUpperCase(Locale.ROOT)))
                .withResponseTimeout(Duration.ofMillis(c.responseTimeout())).withRetries(c.retries())
                .withInterFrameDelay(Duration.ofNanos(Math.round(c.interFrameDelay() * 1e6)))
                .withFaultAfter(Duration.ofMillis(c.faultAfter()));
        bus = ModbusBuses.open(settings);
        Dictionary<String, Object> props = new Hashtable<>();
        props.put("sabot.bus", describe());
        sact = context.registerService(SactClient.class, bus.sact(), props);
        ins = context.registerService(InsClient.class, bus.ins(), props);
        sonar = context.registerService(SonarClient.class, bus.sonar(), props);
        landmark = context.registerService(LandmarkClient.class, bus.landmark(), props);
        boards = context.registerService(RobotBoards.class, new ModbusBoards(bus), props);
        LOG.info("bus open on {} ({}), motor board firmware {}", describe(), bus.timing(),
                bus.sact().config().firmwareVersion());
    }

    @Deactivate
    void deactivate() {
        for (ServiceRegistration<?> r : new ServiceRegistration<?>[] { boards, landmark, sonar, ins, sact }) {
            if (r != null) {
                r.unregister();
            }
        }
        bus.close();
        LOG.info("bus closed: {}", bus.statistics());
    }

    private String describe() {
        return config.tcpHost().isBlank() ? config.port() : config.tcpHost() + ":" + config.tcpPort();
    }

    @Override
    public String name() {
        return "bus";
    }

    @Override
    public String status() {
        return describe() + ": " + bus.statistics();
    }
}
