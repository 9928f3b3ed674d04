package sabot.identity;

import java.util.Map;
import java.util.WeakHashMap;

import org.jivesoftware.smack.Manager;
import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.provider.ProviderManager;
import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jivesoftware.smackx.vcardtemp.packet.VCard;
import org.jxmpp.jid.EntityBareJid;

import sabot.identity.provider.DeviceVCardProvider;

/**
 * Publishes this device's identity (vCard with the inventory QR code as PHOTO) and reads other devices' identities,
 * on one connection ({@link #getInstanceFor(XMPPConnection)}). vCards are stored by the server (vcard-temp), so
 * a device's identity can be read while it is offline.
 */
public final class DeviceIdentityManager extends Manager {

    private static final Map<XMPPConnection, DeviceIdentityManager> INSTANCES = new WeakHashMap<>();

    /** Replaces Smack's vcard-temp provider with one that keeps GEO and FN (it still returns a VCard). */
    public static void registerProvider() {
        ProviderManager.addIQProvider(VCard.ELEMENT, VCard.NAMESPACE, new DeviceVCardProvider());
    }

    /** @return the manager of a connection */
    public static synchronized DeviceIdentityManager getInstanceFor(XMPPConnection connection) {
        registerProvider();
        return INSTANCES.computeIfAbsent(connection, DeviceIdentityManager::new);
    }

    private DeviceIdentityManager(XMPPConnection connection) {
        super(connection);
    }

    /**
     * Publishes the profile with the inventory's QR code as PHOTO.
     *
     * @return what was put in the QR code, or why nothing was published (inventory too large, server refused)
     */
    public IdentityResult<QrInventory.Encoded> publish(DeviceProfile profile, Inventory inventory) {
        IdentityResult<QrInventory.Encoded> qr = QrInventory.encode(inventory);
        if (qr instanceof IdentityResult.Err<QrInventory.Encoded>) {
            return qr;
        }
        try {
            VCardManager.getInstanceFor(connection()).saveVCard(DeviceVCards.of(profile, qr.orElseThrow().png()));
            return qr;
        } catch (XMPPException.XMPPErrorException e) {
            return IdentityResult.err(IdentityResult.Problem.XMPP_FAILURE, "the server refused the vCard: " + e
                    .getStanzaError().getCondition());
        } catch (SmackException | InterruptedException e) {
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            }
            return IdentityResult.err(IdentityResult.Problem.XMPP_FAILURE, "publishing the vCard failed: " + e);
        }
    }

    /** @return a device's profile and inventory, read from its stored vCard */
    public IdentityResult<DeviceCard> fetch(EntityBareJid device) {
        VCard vcard;
        try {
            vcard = VCardManager.getInstanceFor(connection()).loadVCard(device);
        } catch (XMPPException.XMPPErrorException e) {
            if (e.getStanzaError().getCondition() == StanzaError.Condition.item_not_found
                    || e.getStanzaError().getCondition() == StanzaError.Condition.service_unavailable) {
                return IdentityResult.err(IdentityResult.Problem.NO_VCARD, device + " has no vCard");
            }
            return IdentityResult.err(IdentityResult.Problem.XMPP_FAILURE, "vCard of " + device + ": " + e
                    .getStanzaError().getCondition());
        } catch (SmackException | InterruptedException e) {
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            }
            return IdentityResult.err(IdentityResult.Problem.XMPP_FAILURE, "vCard of " + device + ": " + e);
        }
        VCard card = vcard;
        if (card.getField("FN") == null && card.getLastName() == null && card.getJabberId() == null && card
                .getAvatar() == null) {
            return IdentityResult.err(IdentityResult.Problem.NO_VCARD, device + " has an empty vCard");
        }
        IdentityResult<DeviceProfile> profile = DeviceVCards.profileOf(card);
        if (profile instanceof IdentityResult.Err<DeviceProfile> e) {
            return IdentityResult.err(e.problem(), device + ": " + e.text());
        }
        byte[] photo = card.getAvatar();
        if (photo == null) {
            return new IdentityResult.Ok<>(new DeviceCard(profile.orElseThrow(), null, "no PHOTO"));
        }
        IdentityResult<Inventory> inventory = QrInventory.decode(photo);
        if (inventory instanceof IdentityResult.Err<Inventory> e) {
            return new IdentityResult.Ok<>(new DeviceCard(profile.orElseThrow(), null, e.text()));
        }
        return new IdentityResult.Ok<>(new DeviceCard(profile.orElseThrow(), inventory.orElseThrow(), null));
    }
}
