package sabot.controlml;

import java.time.Duration;
import java.time.Instant;
import java.util.Objects;

import org.jxmpp.jid.Jid;

/**
 * A request as a handler sees it: who, which id, and how old.
 *
 * @param from     the requester's JID as stamped by the server; never null
 * @param id       the ControlML id; never null
 * @param resource the resource name; never null
 * @param carrier  what it arrived in; never null
 * @param sent     when it was sent, on the device's clock: a set's {@code sent} moved by the requester's measured
 *                 clock offset, or the XEP-0203 delay stamp the server added while holding it when that is
 *                 earlier, else the time it arrived; never null
 * @param age      how long ago it was sent (zero when it carried neither stamp; negative when its send time is
 *                 ahead of the device's clock); never null
 * @param role     the requester's role on the device when the request arrived (a handler whose command needs more
 *                 than the resource's role, e.g. a maintenance switch, judges by it); never null
 */
public record Request(Jid from, RequestId id, String resource, Carrier carrier, Instant sent, Duration age,
        Role role) {
    public Request {
        Objects.requireNonNull(from, "from");
        Objects.requireNonNull(id, "id");
        Objects.requireNonNull(resource, "resource");
        Objects.requireNonNull(carrier, "carrier");
        Objects.requireNonNull(sent, "sent");
        Objects.requireNonNull(age, "age");
        Objects.requireNonNull(role, "role");
    }
}
