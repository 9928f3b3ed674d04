/**
 * The Modbus RTU master of the robot's RS-485 bus (docs/SACT-MODBUS.md): the SACT motor board, the inertial board,
 * the sonar board, the ceiling-landmark board and the power board, over a serial line or RTU-over-TCP, function codes 0x14/0x15 only. Open a bus with
 * {@link sabot.modbus.ModbusBuses#open(BusSettings)}; every register address comes from the packaged
 * {@code sact-modbus-map.json}. All values are SI (m, s, rad, A, T, °C) unless a name says otherwise; nothing
 * returned is {@code null} unless its Javadoc says so.
 */
package sabot.modbus;
