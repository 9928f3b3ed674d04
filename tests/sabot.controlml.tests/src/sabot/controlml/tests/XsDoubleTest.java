package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import sabot.controlml.swe.SweFormatException;
import sabot.controlml.swe.SweXml;

/** Numbers are read in the xs:double lexical space (XSD 1.0 part 2, 3.2.5.1) and nothing else. */
class XsDoubleTest {

    @ParameterizedTest
    @ValueSource(strings = { "0", "-0", "+1", "1.", ".5", "-.5", "1.25", "12e3", "1E-4", "-2.0E-4", "+3.5e+2", "007",
        " 1.5 ", "NaN", "INF", "+INF", "-INF" })
    void acceptsTheLexicalSpace(String text) throws Exception {
        assertEquals(Double.parseDouble(text.strip().replace("INF", "Infinity")), SweXml.parseDouble(text));
    }

    @ParameterizedTest
    @ValueSource(strings = { "", " ", "+", "-", ".", "e3", "1e", "1e+", "1.5.2", "1,5", "0x1p3", "1d", "1f", "Infinity",
        "nan", "inf", "1 2", "--1", "+-1", "1e3.5", "١" })
    void refusesEverythingElse(String text) {
        SweFormatException e = assertThrows(SweFormatException.class, () -> SweXml.parseDouble(text));
        assertEquals(SweFormatException.Problem.MALFORMED, e.problem());
    }
}
