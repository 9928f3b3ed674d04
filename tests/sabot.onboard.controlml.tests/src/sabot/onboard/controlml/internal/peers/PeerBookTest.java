package sabot.onboard.controlml.internal.peers;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.time.ZoneId;
import java.time.ZoneOffset;
import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;

/** What a robot keeps of the robots it follows, on a clock the test moves by hand. */
class PeerBookTest {

    static final String B = "sabot-02@sabot.local", C = "sabot-03@sabot.local";
    static final Pose2D POSE = new Pose2D(2.5, -1.25, 0.75), LATER = new Pose2D(2.6, -1.2, 0.8);
    static final Twist2D TWIST = new Twist2D(0.3, -0.2);

    /** This robot's clock, moved by the test. */
    static final class HandClock extends Clock {
        Instant now = Instant.parse("2026-11-21T10:00:00Z");

        @Override
        public Instant instant() {
            return now;
        }

        @Override
        public ZoneId getZone() {
            return ZoneOffset.UTC;
        }

        @Override
        public Clock withZone(ZoneId zone) {
            throw new UnsupportedOperationException();
        }
    }

    final HandClock clock = new HandClock();
    final PeerBook book = new PeerBook(clock);

    @Test
    void aFollowedRobotAppearsWithItsFirstPoseStampedWithThisRobotsClock() {
        book.follow(B);
        assertEquals(List.of(), book.peers(), "nothing heard yet");
        Instant heard = clock.now;
        book.pose(B, POSE);
        clock.now = clock.now.plusSeconds(3); // later reads do not restamp it
        assertEquals(List.of(new PeerRobot(B, POSE, Twist2D.ZERO, heard, true)), book.peers());
        book.pose(B, LATER);
        assertEquals(List.of(new PeerRobot(B, LATER, Twist2D.ZERO, clock.now, true)), book.peers());
    }

    @Test
    void aVelocityBeforeTheFirstPoseIsKeptForIt() {
        book.follow(B);
        book.velocity(B, TWIST);
        assertEquals(List.of(), book.peers(), "no pose, no entry");
        book.pose(B, POSE);
        assertEquals(TWIST, book.peers().get(0).velocity());
    }

    @Test
    void telemetryOfARobotNotFollowedIsDropped() {
        book.follow(B);
        book.pose(C, POSE);
        book.velocity(C, TWIST);
        book.online(C, false);
        assertEquals(List.of(), book.peers());
        assertEquals(java.util.Set.of(B), book.followed());
    }

    @Test
    void aRobotGoneOfflineKeepsItsLastPoseUntilItIsNoLongerFollowed() {
        book.follow(B);
        book.pose(B, POSE);
        book.velocity(B, TWIST);
        Instant heard = clock.now;
        clock.now = clock.now.plus(Duration.ofMinutes(5));
        book.online(B, false);
        assertEquals(List.of(new PeerRobot(B, POSE, TWIST, heard, false)), book.peers(), "its body is still there");
        book.online(B, true);
        assertEquals(true, book.peers().get(0).online());
        book.unfollow(B);
        assertEquals(List.of(), book.peers());
        book.pose(B, LATER);
        assertEquals(List.of(), book.peers(), "an item still on its way after it was let go");
    }

    @Test
    void aSnapshotIsImmutableAndLaterTelemetryMakesANewOne() {
        book.follow(B);
        book.follow(C);
        book.pose(C, LATER);
        book.pose(B, POSE);
        List<PeerRobot> before = book.peers();
        assertSame(before, book.peers(), "reading makes no copy");
        assertEquals(List.of(B, C), before.stream().map(PeerRobot::jid).toList(), "sorted by JID");
        book.velocity(B, TWIST);
        assertEquals(Twist2D.ZERO, before.get(0).velocity(), "an old snapshot does not change");
        assertEquals(TWIST, book.peers().get(0).velocity());
        assertThrows(UnsupportedOperationException.class, () -> before.add(before.get(0)));
    }

    @Test
    void aPassageClaimIsKeptWithTheRobotUntilItSaysNone() {
        PassageClaim claim = new PassageClaim(1, PassageClaim.State.WAITING, clock.now.minusSeconds(2));
        book.follow(B);
        book.passage(B, claim);
        assertEquals(List.of(), book.peers(), "no pose, no entry");
        book.pose(B, POSE);
        assertEquals(claim, book.peers().get(0).passage());
        PassageClaim passing = new PassageClaim(1, PassageClaim.State.PASSING, claim.since());
        book.passage(B, passing);
        assertEquals(passing, book.peers().get(0).passage());
        book.passage(B, null);
        assertEquals(null, book.peers().get(0).passage(), "cm.passage said none");
        book.passage(C, claim);
        assertEquals(List.of(B), book.peers().stream().map(PeerRobot::jid).toList(), "a robot not followed");
    }

    @Test
    void clearingForgetsEveryRobot() {
        book.follow(B);
        book.pose(B, POSE);
        book.clear();
        assertEquals(List.of(), book.peers());
        book.pose(B, POSE);
        assertEquals(List.of(), book.peers());
    }
}
