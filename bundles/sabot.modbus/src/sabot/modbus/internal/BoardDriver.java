package sabot.modbus.internal;

import sabot.modbus.Board;
import sabot.modbus.BoardCounters;

/** What the board drivers share: the bus they talk on and their counters. */
abstract class BoardDriver implements Board {

    protected final Bus bus;
    protected final Bus.Counters counters;

    BoardDriver(Bus bus, Bus.Counters counters) {
        this.bus = bus;
        this.counters = counters;
    }

    @Override
    public BoardCounters counters() {
        return counters.snapshot();
    }

    @Override
    public boolean faulted() {
        return counters.faulted();
    }
}
