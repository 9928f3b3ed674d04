package sabot.testsupport.xmpp;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;

import org.jivesoftware.smack.packet.StanzaError.Condition;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlError;
import sabot.controlml.Outcome;

/** Assertions on ControlML answers, as every protocol test states them. */
public final class ControlMlAsserts {

    private ControlMlAsserts() {
    }

    /**
     * The request was refused with this XMPP condition and this ControlML reason, and the error says why in words (an
     * operator reads it).
     */
    public static void assertRefused(Outcome<?> outcome, Condition condition, ControlMlCondition reason) {
        ControlMlError e = outcome.errorOrNull();
        assertNotNull(e, () -> "expected " + condition + "/" + reason.element() + ", got " + outcome);
        assertEquals(condition, e.condition(), e::toString);
        assertEquals(reason, e.cmCondition(), e::toString);
        assertFalse(e.text().isEmpty(), "an operator learns why");
    }
}
