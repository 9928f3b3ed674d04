package sabot.onboard.motion.loop;

import java.io.IOException;
import java.time.Instant;
import java.util.HashSet;
import java.util.Optional;
import java.util.Set;
import java.util.function.DoubleSupplier;
import java.util.function.Supplier;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.localization.MeasurementResult;
import sabot.model.geometry.Pose2D;
import sabot.model.robot.BatteryState;
import sabot.modbus.LandmarkSighting;
import sabot.modbus.WheelCounts;

/**
 * Which board the loop reads in which period. The line carries two transactions per period with the margin the
 * schedule needs (115200 baud: encoder read 5.2 ms + wheel write 4.8 ms of wire time, each after a 1.75 ms silence), not
 * three. So the encoders are read every other period and a sensor board in the periods between (the encoder counts
 * are cumulative: read at 25 Hz they lose no distance; the estimate is predicted in between). The same while a joystick
 * drives: the collision guard needs the sonar then most.
 * <p>
 * In a spare slot: every other one goes to the gyro; one in {@link #LANDMARK_SLOTS} to the landmark board (it measures
 * at 10 Hz), one in {@link #BATTERY_SLOTS} to the power board (a battery changes over minutes: about once a second),
 * the others to the sonar sensors in turn. Each reading is stamped when its answer arrived. Used by the loop's thread
 * only, but for {@link #battery()} and {@link #batteryFault()}, which any thread may read.
 */
final class SensorRounds {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.motion");

    /** One spare slot in this many goes to the landmark board (about 6 Hz at 50 Hz; the board measures at 10). */
    static final int LANDMARK_SLOTS = 8;
    /** Seconds between two reads of a landmark board that has stopped answering. */
    static final double LANDMARK_RETRY = 2.0;
    /**
     * One spare slot in this many goes to the power board (about 1 Hz at 50 Hz), the slot {@link #BATTERY_SLOT} of
     * them: a multiple of {@link #LANDMARK_SLOTS} and an odd slot other than the landmark's, so neither takes the
     * other's turn.
     */
    static final int BATTERY_SLOTS = 3 * LANDMARK_SLOTS;
    static final int BATTERY_SLOT = 3;
    /** Seconds between two reads of a power board that has stopped answering. */
    static final double BATTERY_RETRY = 5.0;

    private final RobotBoards boards;
    private final Localizer localizer;
    private final EchoMemory echoes;
    /** The loop's clock, s: when an answer arrived. */
    private final DoubleSupplier now;
    /** Periods since the start: the even ones read the encoders, the odd ones a sensor board. */
    private long periodCount;
    private int spareSlot;
    private int sonarRound;
    private int lastLandmarkSequence = -1;
    private double lastLandmarkTry = Double.NEGATIVE_INFINITY;
    private final Set<Integer> unknownLandmarks = new HashSet<>();
    /** The loop's wall clock: a battery reading's stamp. */
    private final Supplier<Instant> wall;
    private double lastBatteryTry = Double.NEGATIVE_INFINITY;
    /** The last good battery reading (null before the first), and why the last read failed ("" when it did not). */
    private volatile BatteryState battery;
    private volatile String batteryFault = "";

    SensorRounds(RobotBoards boards, Localizer localizer, EchoMemory echoes, DoubleSupplier now,
            Supplier<Instant> wall) {
        this.boards = boards;
        this.localizer = localizer;
        this.echoes = echoes;
        this.now = now;
        this.wall = wall;
    }

    /** @return the last good battery reading, empty before the first */
    Optional<BatteryState> battery() {
        return Optional.ofNullable(battery);
    }

    /**
     * @return why the power board's last read failed, for a person (e.g. "power: state_of_charge 12000 is outside the
     *         register map's bounds [0, 10000]"); empty when it succeeded
     */
    String batteryFault() {
        return batteryFault;
    }

    /**
     * Counts a period.
     *
     * @return whether this period reads a sensor board after the wheel write instead of the encoders before it
     */
    boolean isSensorPeriod() {
        return (periodCount++ & 1) == 1;
    }

    /** A failed read is not an error by itself: the localizer's odometry timeout and the bus's fault time judge. */
    void readEncoders() {
        try {
            WheelCounts c = boards.readEncoders();
            // stamped when the answer arrived, not when the period began: a retried read is tens of ms late, and
            // odometry's speed is distance over the time between two readings
            localizer.encoders(now.getAsDouble(), c.left(), c.right());
        } catch (IOException e) {
            LOG.debug("encoder read failed: {}", e.getMessage());
        }
    }

    /**
     * Reads the board whose turn it is in this spare slot: the gyro, the landmark board or one sonar sensor.
     *
     * @param t    the period's time, s
     * @param pose the estimate the period started from (places the sonar's echoes on the map)
     */
    void readSpareSlot(double t, Pose2D pose) throws IOException {
        int sonars = boards.sonarSensors();
        int slot = spareSlot++;
        if (slot % LANDMARK_SLOTS == 1 && landmarkReadDue(t)) {
            readLandmark();
        } else if (slot % BATTERY_SLOTS == BATTERY_SLOT && batteryReadDue(t)) {
            readBattery();
        } else if (slot % 2 == 0 || sonars == 0) {
            RobotBoards.ImuSample s = boards.readImu();
            localizer.inertial(now.getAsDouble(), s.yawRate(), s.forwardAcceleration());
        } else {
            int sensor = sonarRound++ % sonars;
            Optional<SonarPing> ping = boards.readSonar(sensor);
            if (ping.isPresent()) {
                echoes.add(t, pose, ping.get());
            }
        }
    }

    /** A landmark board that stopped answering is asked again only every {@link #LANDMARK_RETRY} s. */
    private boolean landmarkReadDue(double t) {
        if (!localizer.usesLandmarks()) {
            return false;
        }
        if (boards.landmarkBoardFaulted() && t - lastLandmarkTry < LANDMARK_RETRY) {
            return false;
        }
        lastLandmarkTry = t;
        return true;
    }

    /** A power board that stopped answering is asked again only every {@link #BATTERY_RETRY} s. */
    private boolean batteryReadDue(double t) {
        if (boards.powerBoardFaulted() && t - lastBatteryTry < BATTERY_RETRY) {
            return false;
        }
        lastBatteryTry = t;
        return true;
    }

    /** A failed read keeps the last good reading (its stamp says how old) and says why in the fault. */
    private void readBattery() {
        try {
            BatteryState b = boards.readBattery(wall.get());
            battery = b;
            if (!batteryFault.isEmpty()) {
                LOG.info("power board answers again: {}", b.summary());
            }
            batteryFault = "";
        } catch (IOException e) {
            String why = e.getMessage() == null ? e.getClass().getSimpleName() : e.getMessage();
            if (!why.equals(batteryFault)) {
                LOG.warn("battery reading refused: {}", why);
            }
            batteryFault = why;
        }
    }

    private void readLandmark() throws IOException {
        LandmarkSighting s = boards.readLandmark();
        if (s.sequence() == lastLandmarkSequence) {
            return; // read again before the board measured anew
        }
        lastLandmarkSequence = s.sequence();
        if (s.seen()) {
            MeasurementResult r = localizer.landmark(now.getAsDouble(), s.landmarkId(), s.range(), s.bearing(),
                    s.age().toNanos() * 1e-9);
            if (r == null && unknownLandmarks.add(s.landmarkId())) {
                LOG.warn("landmark {} seen but not on the map's landmark list: ignored", s.landmarkId());
            }
        }
    }
}
