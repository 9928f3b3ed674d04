package sabot.workbench.controlml.internal;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;

import sabot.controlml.ControlMlManager;

/**
 * The connection of one login and what hangs on it. Work queued for a session checks that it is still the current
 * one ({@link FleetConnection#session()}): an older session's callbacks change nothing.
 */
record FleetSession(XMPPTCPConnection connection, ControlMlManager manager, Roster roster, long generation) {
}
