package sabot.fleet.internal;

import java.util.List;

import org.jivesoftware.smack.packet.IQ;
import org.jxmpp.jid.DomainBareJid;
import org.jxmpp.jid.EntityBareJid;

import sabot.fleet.ArchivedCommand;

/** The command history's IQ (sabot.fleet.CommandHistory): the request, or the server's answer with its commands. */
public final class HistoryIq extends IQ {

    /** The protocol's namespace. */
    public static final String NAMESPACE = "urn:sabot:archive:1";
    /** The request's and the answer's element. */
    public static final String ELEMENT = "history";

    private final EntityBareJid device;
    private final int max;
    private final long before;
    private final List<ArchivedCommand> commands;
    private final List<String> problems;

    private HistoryIq(EntityBareJid device, int max, long before, List<ArchivedCommand> commands,
            List<String> problems) {
        super(ELEMENT, NAMESPACE);
        this.device = device;
        this.max = max;
        this.before = before;
        this.commands = List.copyOf(commands);
        this.problems = List.copyOf(problems);
    }

    /**
     * @param before 0, or the seq of a command: those taken before it
     * @return a get of {@code device}'s latest {@code max} commands, to the server's domain
     */
    public static HistoryIq request(DomainBareJid server, EntityBareJid device, int max, long before) {
        HistoryIq iq = new HistoryIq(device, max, before, List.of(), List.of());
        iq.setType(Type.get);
        iq.setTo(server);
        return iq;
    }

    /** @return an answer as read: its commands, and what could not be read */
    static HistoryIq answer(List<ArchivedCommand> commands, List<String> problems) {
        return new HistoryIq(null, 0, 0, commands, problems);
    }

    /** @return the commands of an answer, newest first */
    public List<ArchivedCommand> commands() {
        return commands;
    }

    /** @return the commands of the answer that could not be read, and why; empty when all could */
    public List<String> problems() {
        return problems;
    }

    @Override
    protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
        xml.optAttribute("device", device);
        if (max > 0) {
            xml.attribute("max", max);
        }
        if (before > 0) {
            xml.attribute("before", Long.toString(before));
        }
        xml.setEmptyElement();
        return xml;
    }
}
