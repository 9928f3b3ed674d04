package sabot.fleet;

import java.util.Collection;

import org.jivesoftware.smack.roster.AbstractRosterListener;
import org.jxmpp.jid.Jid;

/**
 * A roster listener for whoever only needs to know that the roster's entries changed (added, updated or deleted, by a
 * push or a reload), not which: a device's roles, a workbench's robots.
 */
public abstract class RosterEntriesListener extends AbstractRosterListener {

    /** Some entries were added, updated or deleted (on Smack's listener thread). */
    protected abstract void entriesChanged();

    @Override
    public final void entriesAdded(Collection<Jid> addresses) {
        entriesChanged();
    }

    @Override
    public final void entriesUpdated(Collection<Jid> addresses) {
        entriesChanged();
    }

    @Override
    public final void entriesDeleted(Collection<Jid> addresses) {
        entriesChanged();
    }
}
