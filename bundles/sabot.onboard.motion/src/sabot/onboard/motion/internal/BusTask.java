package sabot.onboard.motion.internal;

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
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;
import org.osgi.service.metatype.annotations.Option;
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
import sabot.onboard.motion.loop.RobotBoards;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code bus}: the robot's RS-485 line (Modbus RTU master on a serial device, or RTU framing over TCP) and the
 * board clients on it, registered as services ({@link SactClient}, {@link InsClient}, {@link SonarClient},
 * {@link LandmarkClient}: the landmark board is optional) and as the control loop's {@link RobotBoards}. Settings:
 * {@link Config}.
 */
@Designate(ocd = BusTask.Config.class, factory = false)
@Component(name = "sabot.task.bus", configurationPolicy = ConfigurationPolicy.REQUIRE, service = OnboardTask.class)
public final class BusTask implements OnboardTask {

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = "sabot.task.bus", name = "Bus task",
            description = "The robot's RS-485 line: Modbus RTU master (0x14/0x15) of the motor, inertial and sonar "
                    + "boards.")
    public @interface Config {
        @AttributeDefinition(name = "Serial port", description = "Serial device, e.g. /dev/ttyUSB0 or the "
                + "simulator's pty link; empty when tcpHost is set.")
        String port() default "";

        @AttributeDefinition(name = "TCP host", description = "Host of an RTU-over-TCP gateway (or sabot-sim --tcp); "
                + "empty for a serial line.")
        String tcpHost() default "";

        @AttributeDefinition(name = "TCP port", description = "TCP port of the gateway.", min = "1", max = "65535")
        int tcpPort() default 502;

        @AttributeDefinition(name = "Baud rate", description = "Bit rate of the line, bit/s.", min = "1200",
                max = "4000000")
        int baud() default 115200;

        @AttributeDefinition(name = "Parity", description = "EVEN on the SACT bus; NONE on a pseudo-terminal (Linux "
                + "refuses parity on ptys).", options = { @Option(label = "Even", value = "EVEN"),
                        @Option(label = "None", value = "NONE"), @Option(label = "Odd", value = "ODD") })
        String parity() default "EVEN";

        @AttributeDefinition(name = "Response timeout", description = "Milliseconds to wait for a board's answer.",
                min = "1", max = "10000")
        int responseTimeout() default 50;

        @AttributeDefinition(name = "Retries", description = "Retries after a timeout or a corrupt answer.",
                min = "0", max = "10")
        int retries() default 1;

        @AttributeDefinition(name = "Inter-frame delay", description = "Milliseconds of silence between frames "
                + "(t3.5; 1.75 ms above 19200 baud).", min = "0", max = "1000")
        double interFrameDelay() default 1.75;

        @AttributeDefinition(name = "Fault after", description = "Milliseconds without a good answer after which a "
                + "board is faulted and the robot stops.", min = "1", max = "60000")
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
