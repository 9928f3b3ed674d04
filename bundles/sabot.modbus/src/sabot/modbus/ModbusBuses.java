package sabot.modbus;

import java.io.IOException;

import sabot.modbus.internal.Bus;

/** Opens buses. */
public final class ModbusBuses {

    private ModbusBuses() {
    }

    /**
     * Opens the port (or connects the socket) and reads the SACT board's configuration. A SACT board that does not
     * answer does not stop the bus from opening: {@link SactClient#config()} then tries again.
     *
     * @param settings where and how
     * @return the open bus
     * @throws IOException the port does not exist or cannot be opened, or the TCP peer refuses; the message names it
     */
    public static ModbusBus open(BusSettings settings) throws IOException {
        return Bus.open(settings);
    }
}
