package sabot.modbus;

/** One of the SACT board's two motors; each has its own file in the register map. */
public enum Motor {
    /** the left wheel's motor (map file {@code motor_left}) */
    LEFT("motor_left"),
    /** the right wheel's motor (map file {@code motor_right}) */
    RIGHT("motor_right");

    private final String file;

    Motor(String file) {
        this.file = file;
    }

    /** @return the motor's file name in the register map */
    public String mapFile() {
        return file;
    }
}
