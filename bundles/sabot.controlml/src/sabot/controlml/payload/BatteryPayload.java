package sabot.controlml.payload;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.SweComponent;
import sabot.model.robot.BatteryState;

/**
 * {@code cm.battery}: the robot's battery as its power board last measured it ({@link BatteryState}, in
 * {@code sabot.model.robot}, the value the onboard loop holds). The state of charge travels in per cent, as
 * {@code cm.mission}'s progress does.
 */
public final class BatteryPayload {

    /** Bounds of the protocol, beyond any battery a robot carries: a value outside is a malformed reading. */
    static final double MAX_VOLTAGE = 1000;
    static final double MAX_CURRENT = 1000;
    static final double MAX_CAPACITY = 1000;

    private BatteryPayload() {
    }

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<BatteryState> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(BatteryState b) {
            return new RecordBuilder().time("time", b.measured()).quantity("stateOfCharge", "%", b.stateOfCharge()
                    * 100).quantity("voltage", "V", b.voltage()).quantity("current", "A", b.current()).quantity(
                            "capacity", "A.h", b.designCapacity()).bool("docked", b.docked()).bool("charging", b
                                    .charging()).bool("full", b.full()).build();
        }

        @Override
        public BatteryState decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "stateOfCharge", "voltage", "current", "capacity",
                    "docked", "charging", "full");
            try {
                return new BatteryState(r.time("time"), r.quantity("stateOfCharge", "%", 0, 100) / 100, r.quantity(
                        "voltage", "V", Double.MIN_VALUE, MAX_VOLTAGE), r.quantity("current", "A", -MAX_CURRENT,
                                MAX_CURRENT), r.quantity("capacity", "A.h", Double.MIN_VALUE, MAX_CAPACITY), r.bool(
                                        "docked"), r.bool("charging"), r.bool("full"));
            } catch (IllegalArgumentException e) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, e.getMessage());
            }
        }
    };
}
