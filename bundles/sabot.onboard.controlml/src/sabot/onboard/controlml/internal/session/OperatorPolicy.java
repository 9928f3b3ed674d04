package sabot.onboard.controlml.internal.session;

import java.util.Set;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.packet.RosterPacket;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;

import sabot.controlml.AccessLevel;
import sabot.controlml.AccessPolicy;

/**
 * Who may command the robot (docs/CONTROLML.md §9, the robot's side of {@code sabot.fleet.AccessRules}):
 * <ul>
 * <li>the configured operators may set (and get);</li>
 * <li>contacts with a mutual presence subscription in the robot's roster may set when no operator is configured,
 * and only get otherwise (they see the robot's presence and telemetry: the robot's owner accepted them);</li>
 * <li>everyone else is refused ({@code forbidden}).</li>
 * </ul>
 * The roster is read at each request, so adding or removing a contact takes effect at once.
 */
final class OperatorPolicy implements AccessPolicy {

    private final Set<EntityBareJid> operators;
    private final Roster roster;

    OperatorPolicy(Set<EntityBareJid> operators, Roster roster) {
        this.operators = Set.copyOf(operators);
        this.roster = roster;
    }

    @Override
    public AccessLevel levelOf(Jid requester) {
        BareJid bare = requester.asBareJid();
        if (operators.contains(bare)) {
            return AccessLevel.SET;
        }
        if (isMutualContact(bare)) {
            return operators.isEmpty() ? AccessLevel.SET : AccessLevel.GET;
        }
        return AccessLevel.NONE;
    }

    /** @return true when the roster holds the JID with a subscription in both directions */
    boolean isMutualContact(BareJid jid) {
        RosterEntry entry = roster.getEntry(jid);
        return entry != null && entry.getType() == RosterPacket.ItemType.both;
    }

    /**
     * Whether to approve a presence subscription request: from anyone who may at least get, and from anyone the
     * robot's owner already put in its roster (so that a contact added by the owner can become mutual).
     */
    boolean approvesSubscription(Jid from) {
        return levelOf(from) != AccessLevel.NONE || roster.getEntry(from.asBareJid()) != null;
    }
}
