package sabot.fleet.internal;

import org.jivesoftware.smack.packet.IQ;
import org.jxmpp.jid.DomainBareJid;
import org.jxmpp.jid.EntityBareJid;

import sabot.fleet.ServerFigures;

/** The statistics' IQ (sabot.fleet.ServerStatistics): the request, or the server's answer with the figures. */
public final class StatisticsIq extends IQ {

    /** The request's and the answer's element, in the archive's namespace ({@link HistoryIq#NAMESPACE}). */
    public static final String ELEMENT = "statistics";

    private final EntityBareJid device;
    private final long seconds;
    private final ServerFigures figures;
    private final String problem;

    private StatisticsIq(EntityBareJid device, long seconds, ServerFigures figures, String problem) {
        super(ELEMENT, HistoryIq.NAMESPACE);
        this.device = device;
        this.seconds = seconds;
        this.figures = figures;
        this.problem = problem;
    }

    /** @return a get of {@code device}'s figures over the last {@code seconds}, to the server's domain */
    public static StatisticsIq request(DomainBareJid server, EntityBareJid device, long seconds) {
        StatisticsIq iq = new StatisticsIq(device, seconds, null, null);
        iq.setType(Type.get);
        iq.setTo(server);
        return iq;
    }

    /** @return an answer as read: its figures, or why they could not be read */
    static StatisticsIq answer(ServerFigures figures, String problem) {
        return new StatisticsIq(null, 0, figures, problem);
    }

    /** @return the figures of an answer; null when they could not be read ({@link #problem()}) */
    public ServerFigures figures() {
        return figures;
    }

    /** @return why the answer could not be read, or null */
    public String problem() {
        return problem;
    }

    @Override
    protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
        xml.optAttribute("device", device);
        if (seconds > 0) {
            xml.attribute("seconds", Long.toString(seconds));
        }
        xml.setEmptyElement();
        return xml;
    }
}
