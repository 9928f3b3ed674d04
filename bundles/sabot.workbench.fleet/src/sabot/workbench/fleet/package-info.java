/**
 * The workbench's fleet as its core and plug-ins observe it (thesis rule 1: the ControlML plug-in is the subject,
 * the core's views and the other plug-ins are its observers). {@link sabot.workbench.fleet.FleetState} is an OSGi
 * service; its values are immutable snapshots in SI units (metres, radians, seconds) in the map frame. No XMPP or SWT
 * type appears here: views never touch the connection.
 */
package sabot.workbench.fleet;
