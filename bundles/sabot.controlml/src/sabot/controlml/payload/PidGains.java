package sabot.controlml.payload;

import java.util.List;

/** {@code cm.pid}: gains per motor, motors unique. @param motors the gains; never null */
public record PidGains(List<MotorGains> motors) {
    public PidGains {
        motors = List.copyOf(motors);
    }
}
