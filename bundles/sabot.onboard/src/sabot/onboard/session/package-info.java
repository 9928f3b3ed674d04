/**
 * The robot's XMPP session as a service: one connection per robot, its ControlML manager, presence and identity.
 * Provided by {@code sabot.task.controlml}; tasks that serve a resource or publish telemetry reference it.
 */
package sabot.onboard.session;
