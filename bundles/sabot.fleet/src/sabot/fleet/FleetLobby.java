package sabot.fleet;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smackx.muc.MultiUserChat;
import org.jivesoftware.smackx.muc.MultiUserChatManager;
import org.jivesoftware.smackx.muc.Occupant;
import org.jivesoftware.smackx.xdata.form.FillableForm;
import org.jivesoftware.smackx.xdata.form.Form;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.EntityFullJid;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.parts.Resourcepart;

/**
 * Where online devices are discovered (roster rule 11): a multi-user chat room (XEP-0045) that every device joins
 * when it comes online and leaves when it goes; occupancy is presence, so the room's occupant list is the list of
 * online devices. The room shows occupants' real JIDs to everyone ({@code muc#roomconfig_whois = anyone}): that is its
 * purpose. Standard on Prosody ({@code muc} component) and ejabberd ({@code mod_muc}); no server plug-in.
 */
public final class FleetLobby {

    private final XMPPConnection connection;
    private final EntityBareJid room;
    private MultiUserChat muc;

    /**
     * @param connection this client's connection
     * @param room       the lobby, e.g. {@code fleet@conference.sabot.local}
     */
    public FleetLobby(XMPPConnection connection, EntityBareJid room) {
        this.connection = Objects.requireNonNull(connection);
        this.room = Objects.requireNonNull(room);
    }

    /**
     * Joins (creating and configuring the room when this client is the first), with the bare JID's local part as
     * nickname.
     *
     * @throws FleetException when the room cannot be joined
     */
    public synchronized void join() throws FleetException {
        MultiUserChat m = MultiUserChatManager.getInstanceFor(connection).getMultiUserChat(room);
        try {
            String nick = connection.getUser().asEntityBareJid().toString().replace('@', '.');
            MultiUserChat.MucCreateConfigFormHandle created = m.createOrJoin(Resourcepart.from(nick));
            if (created != null) {
                Form form = m.getConfigurationForm();
                FillableForm answer = form.getFillableForm();
                if (form.getField("muc#roomconfig_whois") != null) {
                    answer.setAnswer("muc#roomconfig_whois", "anyone");
                }
                m.sendConfigurationForm(answer);
            }
        } catch (XMPPException | SmackException | InterruptedException | java.io.IOException e) {
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            }
            throw new FleetException("cannot join the fleet lobby " + room + ": " + e, e);
        }
        muc = m;
    }

    /** @return the real JIDs of the other occupants (the online devices and workbenches) */
    public synchronized List<Jid> members() {
        List<Jid> out = new ArrayList<>();
        if (muc == null) {
            return out;
        }
        EntityFullJid me = connection.getUser();
        for (EntityFullJid occupantJid : muc.getOccupants()) {
            Occupant o = muc.getOccupant(occupantJid);
            Jid real = o == null ? null : o.getJid();
            if (real != null && !real.equals(me)) {
                out.add(real);
            }
        }
        return out;
    }

    /** Leaves the room. */
    public synchronized void leave() {
        if (muc != null) {
            try {
                muc.leave();
            } catch (SmackException | XMPPException | InterruptedException e) {
                if (e instanceof InterruptedException) {
                    Thread.currentThread().interrupt();
                }
            }
            muc = null;
        }
    }
}
