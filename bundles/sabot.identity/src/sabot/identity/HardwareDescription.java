package sabot.identity;

import java.util.List;
import java.util.Objects;

/**
 * What software cannot find out about a device by itself: its serial, mechanics, board and peripherals (from the
 * robot description and the installation's configuration).
 *
 * @param serial         the serial number on the label; never null
 * @param mechanic       the chassis; never null
 * @param boardName      the embedded PC's name; never null
 * @param specialDevices the peripherals; never null
 */
public record HardwareDescription(String serial, Inventory.Mechanic mechanic, String boardName,
        List<Inventory.SpecialDevice> specialDevices) {
    public HardwareDescription {
        Objects.requireNonNull(serial, "serial");
        Objects.requireNonNull(mechanic, "mechanic");
        Objects.requireNonNull(boardName, "boardName");
        specialDevices = List.copyOf(specialDevices);
    }
}
