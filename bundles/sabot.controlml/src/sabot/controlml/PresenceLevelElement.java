package sabot.controlml;

import java.util.Objects;

import javax.xml.namespace.QName;

import org.jivesoftware.smack.packet.ExtensionElement;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.packet.XmlEnvironment;

/**
 * {@code <presence-level xmlns='urn:sabot:controlml:1' level='busy' mission='running' maintenance='false'/>}: the
 * exact presence level and why, inside a device's {@code <presence/>}.
 */
public final class PresenceLevelElement implements ExtensionElement {

    /** The element name. */
    public static final String ELEMENT = "presence-level";
    /** The qualified name (Smack looks extension classes up by it). */
    public static final QName QNAME = new QName(ControlMl.NAMESPACE, ELEMENT);

    private final PresenceLevel level;
    private final String mission;
    private final boolean maintenance;

    /**
     * @param level       the level; never null
     * @param mission     the mission state attribute (e.g. {@code running}); never null
     * @param maintenance whether the device is in maintenance mode
     */
    public PresenceLevelElement(PresenceLevel level, String mission, boolean maintenance) {
        this.level = Objects.requireNonNull(level);
        this.mission = Objects.requireNonNull(mission);
        this.maintenance = maintenance;
    }

    private PresenceLevelElement() {
        this.level = null;
        this.mission = "";
        this.maintenance = false;
    }

    /**
     * For the provider: a received element that could not be read. Smack cannot drop an extension, so it is kept
     * with a null {@link #level()}, and readers fall back to the presence's show.
     */
    public static PresenceLevelElement unreadable() {
        return new PresenceLevelElement();
    }

    /** @return the level; null only for an {@link #unreadable()} element */
    public PresenceLevel level() {
        return level;
    }

    /** @return the mission state, as the {@code cm.mission} state code */
    public String mission() {
        return mission;
    }

    /** @return true when the device is in maintenance mode */
    public boolean maintenance() {
        return maintenance;
    }

    /** @return the element in a presence, or null */
    public static PresenceLevelElement from(Presence presence) {
        return presence.getExtension(PresenceLevelElement.class);
    }

    @Override
    public String getElementName() {
        return ELEMENT;
    }

    @Override
    public String getNamespace() {
        return ControlMl.NAMESPACE;
    }

    @Override
    public CharSequence toXML(XmlEnvironment xmlEnvironment) {
        if (level == null) {
            return "<" + ELEMENT + " xmlns='" + ControlMl.NAMESPACE + "'/>";
        }
        StringBuilder sb = new StringBuilder(96);
        sb.append('<').append(ELEMENT).append(" xmlns='").append(ControlMl.NAMESPACE).append("' level='").append(
                level.attribute()).append("' mission='");
        sabot.controlml.swe.SweXml.escape(mission, sb);
        return sb.append("' maintenance='").append(maintenance).append("'/>");
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof PresenceLevelElement e && e.level == level && e.mission.equals(mission)
                && e.maintenance == maintenance;
    }

    @Override
    public int hashCode() {
        return Objects.hash(level, mission, maintenance);
    }

    @Override
    public String toString() {
        return toXML(org.jivesoftware.smack.packet.XmlEnvironment.EMPTY).toString();
    }
}
