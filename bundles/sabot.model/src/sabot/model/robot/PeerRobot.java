package sabot.model.robot;

import java.time.Instant;
import java.util.Objects;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/**
 * Another robot of the fleet as this one last heard of it: its pose and velocity from its own telemetry
 * ({@code cm.position}, {@code cm.velocity}), stamped with this robot's clock when the pose arrived. Immutable.
 *
 * @param jid      the other robot's bare JID; never null
 * @param pose     its pose estimate in the map frame; never null
 * @param velocity the twist it is executing (body frame: linear m/s along its heading, angular rad/s); never null
 * @param heard    when the pose arrived, on this robot's clock; never null
 * @param online   false once the other robot went offline (its last pose is kept: its body is still there)
 * @param passage  its claim on a narrow passage ({@code cm.passage}) as last heard, or null for none
 */
public record PeerRobot(String jid, Pose2D pose, Twist2D velocity, Instant heard, boolean online,
        PassageClaim passage) {

    public PeerRobot {
        Objects.requireNonNull(jid, "jid");
        Objects.requireNonNull(pose, "pose");
        Objects.requireNonNull(velocity, "velocity");
        Objects.requireNonNull(heard, "heard");
    }

    /** A robot with no claim on a passage. */
    public PeerRobot(String jid, Pose2D pose, Twist2D velocity, Instant heard, boolean online) {
        this(jid, pose, velocity, heard, online, null);
    }

    /** @return the same robot with that claim (null: none) */
    public PeerRobot withPassage(PassageClaim claim) {
        return new PeerRobot(jid, pose, velocity, heard, online, claim);
    }

    /** @return its velocity along the map's x axis, m/s */
    public double vx() {
        return velocity.linear() * Math.cos(pose.theta());
    }

    /** @return its velocity along the map's y axis, m/s */
    public double vy() {
        return velocity.linear() * Math.sin(pose.theta());
    }
}
