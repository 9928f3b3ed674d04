package sabot.fleet;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.function.Predicate;

import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.roster.Roster;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;

import sabot.identity.DeviceCard;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.IdentityResult;

/**
 * Compiles a workbench's roster when it connects.
 * <ul>
 * <li><b>Rule 11</b>: discover the online devices (the {@link FleetLobby}'s occupants), fetch their vCards, and
 * subscribe to those whose {@link DeviceProfile} satisfies the configured predicate (e.g. manufacturer and role).</li>
 * <li><b>Rule 12</b>: subscribe to a configured list of JIDs on other domains without the vCard check.</li>
 * </ul>
 * Devices already in the roster are left as they are.
 */
public final class RosterCompiler {

    /**
     * @param accept         rule 11's predicate on device profiles (what a device says of itself, in its vCard)
     * @param vouched        rule 11's predicate on a lobby member's JID, checked before its vCard: whether someone
     *                       other than the device vouches for it (e.g. the server's robots' group); a device's own
     *                       vCard is not proof, anyone can write one
     * @param foreignDevices rule 12's JIDs (other domains), subscribed unconditionally
     * @param group          roster group the compiled entries go into
     */
    public record Rules(Predicate<DeviceProfile> accept, Predicate<EntityBareJid> vouched,
            Set<EntityBareJid> foreignDevices, String group) {
        public Rules {
            Objects.requireNonNull(accept, "accept");
            Objects.requireNonNull(vouched, "vouched");
            foreignDevices = Set.copyOf(foreignDevices);
            Objects.requireNonNull(group, "group");
        }

        /** Rules that take each device's vCard at its word (a lab where every account is trusted). */
        public Rules(Predicate<DeviceProfile> accept, Set<EntityBareJid> foreignDevices, String group) {
            this(accept, jid -> true, foreignDevices, group);
        }

        /** @return a predicate matching a manufacturer (N/FAMILY) and a role (ROLE) exactly */
        public static Predicate<DeviceProfile> manufacturerAndRole(String manufacturer, String role) {
            return p -> manufacturer.equals(p.manufacturer()) && role.equals(p.role());
        }
    }

    /**
     * @param subscribed devices subscribed by rule 11
     * @param rejected   discovered entities not subscribed, with the reason
     * @param foreign    devices subscribed by rule 12
     */
    public record Report(List<EntityBareJid> subscribed, Map<EntityBareJid, String> rejected,
            List<EntityBareJid> foreign) {
    }

    private final XMPPConnection workbench;
    private final FleetLobby lobby;
    private final Rules rules;

    public RosterCompiler(XMPPConnection workbench, FleetLobby lobby, Rules rules) {
        this.workbench = Objects.requireNonNull(workbench);
        this.lobby = Objects.requireNonNull(lobby);
        this.rules = Objects.requireNonNull(rules);
    }

    /** Applies both rules now. @return what was done */
    public Report compile() throws FleetException {
        Roster roster = Roster.getInstanceFor(workbench);
        DeviceIdentityManager identities = DeviceIdentityManager.getInstanceFor(workbench);
        List<EntityBareJid> subscribed = new ArrayList<>();
        Map<EntityBareJid, String> rejected = new LinkedHashMap<>();
        for (Jid member : lobby.members()) {
            EntityBareJid device = member.asEntityBareJidIfPossible();
            if (device == null || device.equals(workbench.getUser().asEntityBareJid()) || roster.getEntry(device)
                    != null) {
                continue;
            }
            if (!rules.vouched().test(device)) {
                rejected.put(device, "not vouched for (its own vCard is not proof)");
                continue;
            }
            IdentityResult<DeviceCard> card = identities.fetch(device);
            if (card instanceof IdentityResult.Err<DeviceCard> e) {
                rejected.put(device, e.problem() + ": " + e.text());
                continue;
            }
            DeviceProfile profile = card.orElseThrow().profile();
            if (!rules.accept().test(profile)) {
                rejected.put(device, "profile does not match (" + profile.manufacturer() + ", " + profile.role()
                        + ")");
                continue;
            }
            subscribe(roster, device, profile.nickname());
            subscribed.add(device);
        }
        List<EntityBareJid> foreign = new ArrayList<>();
        for (EntityBareJid device : rules.foreignDevices()) {
            if (roster.getEntry(device) == null) {
                subscribe(roster, device, null);
                foreign.add(device);
            }
        }
        return new Report(subscribed, rejected, foreign);
    }

    private void subscribe(Roster roster, EntityBareJid device, String name) throws FleetException {
        try {
            roster.createItemAndRequestSubscription(device, name == null ? device.getLocalpart().toString() : name,
                    new String[] { rules.group() });
        } catch (XMPPException | SmackException | InterruptedException e) {
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            }
            throw new FleetException("cannot subscribe to " + device + ": " + e, e);
        }
    }
}
