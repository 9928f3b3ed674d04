package sabot.controlml.swe;

import java.io.IOException;
import java.time.Instant;
import java.time.format.DateTimeParseException;
import java.util.ArrayList;
import java.util.List;
import java.util.regex.Pattern;

import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;
import org.osgi.annotation.versioning.ConsumerType;

/**
 * Strict reader and canonical writer of the SWE Common 2.0 subset in {@link SweComponent}.
 * <p>
 * Reading is strict because ControlML is a control protocol: unknown elements or attributes, text where elements
 * belong, numbers in non-xs:double syntax, time stamps without a zone, separators other than {@code ","} and
 * {@code " "} are all refused with {@link SweFormatException.Problem#MALFORMED}. The reader also enforces a size
 * budget (characters of names, attribute values and text, the way they arrive) and a nesting limit, so an
 * oversized payload is refused while it is read, before anything is built from it.
 * <p>
 * Writing emits the canonical form that {@code docs/controlml.xsd} (importing the OGC SWE 2.0 schema) validates:
 * the SWE namespace as default namespace of the payload's root, SI/UCUM codes, {@link Double#toString(double)}
 * numbers (shortest round-tripping form), and {@link Instant#toString()} time stamps.
 */
public final class SweXml {

    /** Deepest nesting of DataRecords the reader accepts. */
    public static final int MAX_NESTING = 8;

    private static final Pattern XS_INTEGER = Pattern.compile("[+-]?\\d{1,18}");
    private static final Pattern NC_NAME = Pattern.compile("[A-Za-z_][A-Za-z0-9_.-]{0,63}");

    private SweXml() {
    }

    /**
     * A size budget, shared by one read, in ControlML's payload size (docs/CONTROLML.md section 1): the payload's
     * length written without namespace declarations, prefixes, comments or processing instructions and with every
     * element as a start and an end tag, in Unicode code points. An element costs its name twice plus 5
     * ({@code <n>}, {@code </n>}), an attribute its name and value plus 4 ({@code  n=''}), text its characters
     * after entity expansion (white space between elements included).
     */
    public static final class Budget {
        private final int limit;
        private int used;

        /** @param limit code points the payload may use */
        public Budget(int limit) {
            this.limit = limit;
        }

        void charge(int chars) throws SweFormatException {
            used += chars;
            if (used > limit) {
                throw new SweFormatException(SweFormatException.Problem.TOO_LARGE, "payload larger than " + limit
                        + " characters");
            }
        }

        /** @return characters charged so far */
        public int used() {
            return used;
        }
    }

    // ------------------------------------------------------------------------------------------------ reading

    /**
     * Reads one component.
     *
     * @param parser positioned at the component's start tag, which is in the SWE namespace
     * @param budget charged with the component's size
     * @return the component; never null
     * @throws SweFormatException when the component is not acceptable; the parser is then somewhere inside it
     */
    public static SweComponent read(XmlPullParser parser, Budget budget) throws SweFormatException,
            XmlPullParserException, IOException {
        return readComponent(parser, budget, 0);
    }

    /** Finds the record structure a {@code DataStream}'s {@code elementType} refers to. */
    @FunctionalInterface
    @ConsumerType
    public interface StructureResolver {
        /** @return the template of {@code href}, or null when the reference is not known here */
        RecordTemplate templateOf(String href);
    }

    /**
     * Reads one payload: a component, or a record in the text form ({@code DataStream} whose {@code elementType}
     * refers to a known structure, see {@link RecordTemplate}), returned as the {@link DataRecord} it encodes.
     *
     * @param parser   positioned at the payload's start tag, which is in the SWE namespace
     * @param budget   charged with the payload's size
     * @param resolver the structures a DataStream may refer to
     * @return the component; never null
     * @throws SweFormatException when the payload is not acceptable; the parser is then somewhere inside it
     */
    public static SweComponent readPayload(XmlPullParser parser, Budget budget, StructureResolver resolver)
            throws SweFormatException, XmlPullParserException, IOException {
        requireSwe(parser);
        if (!"DataStream".equals(parser.getName())) {
            return readComponent(parser, budget, 0);
        }
        chargeStartTag(parser, budget);
        allowAttributes(parser);
        expectChild(parser, budget, "elementType");
        String href = null;
        boolean named = false;
        for (int i = 0; i < parser.getAttributeCount(); i++) {
            String a = parser.getAttributeName(i);
            if (Swe.XLINK_NAMESPACE.equals(parser.getAttributeNamespace(i)) && "href".equals(a)) {
                href = parser.getAttributeValue(i);
            } else if (noNamespace(parser.getAttributeNamespace(i)) && "name".equals(a) && NC_NAME.matcher(parser
                    .getAttributeValue(i)).matches()) {
                named = true;
            } else {
                throw malformed("unexpected attribute " + a + " on DataStream/elementType");
            }
        }
        if (!named || href == null) {
            throw malformed("a DataStream's elementType needs a name and an xlink:href to a record structure");
        }
        RecordTemplate template = resolver.templateOf(href);
        if (template == null) {
            throw malformed("unknown record structure '" + abbreviate(href) + "'");
        }
        expectEnd(parser, budget); // elementType: by reference only
        expectChild(parser, budget, "encoding");
        allowAttributes(parser);
        expectChild(parser, budget, "TextEncoding");
        readTextEncoding(parser);
        expectEnd(parser, budget); // TextEncoding
        expectEnd(parser, budget); // encoding
        expectChild(parser, budget, "values");
        allowAttributes(parser);
        DataRecord record = template.read(readText(parser, budget));
        expectEnd(parser, budget); // DataStream
        return record;
    }

    private static SweComponent readComponent(XmlPullParser p, Budget budget, int nesting) throws SweFormatException,
            XmlPullParserException, IOException {
        requireSwe(p);
        String name = p.getName();
        chargeStartTag(p, budget);
        return switch (name) {
            case "Quantity" -> readQuantity(p, budget);
            case "Count" -> {
                allowAttributes(p, "definition");
                yield new Count(parseLong(readOnlyValue(p, budget)));
            }
            case "Time" -> readTime(p, budget);
            case "Text" -> {
                allowAttributes(p, "definition");
                yield new Text(readOnlyValue(p, budget));
            }
            case "Category" -> {
                allowAttributes(p, "definition");
                yield new Category(readOnlyValue(p, budget));
            }
            case "Boolean" -> {
                allowAttributes(p, "definition");
                String v = readOnlyValue(p, budget);
                yield switch (v) {
                    case "true", "1" -> new SweBoolean(true);
                    case "false", "0" -> new SweBoolean(false);
                    default -> throw malformed("not an xs:boolean: '" + abbreviate(v) + "'");
                };
            }
            case "DataRecord" -> readRecord(p, budget, nesting);
            case "DataArray" -> readArray(p, budget);
            default -> throw malformed("SWE component " + name + " is not part of ControlML");
        };
    }

    private static Quantity readQuantity(XmlPullParser p, Budget budget) throws SweFormatException,
            XmlPullParserException, IOException {
        allowAttributes(p, "definition");
        expectChild(p, budget, "uom");
        String code = uomCode(p);
        expectEnd(p, budget);
        expectChild(p, budget, "value");
        allowAttributes(p);
        double value = parseDouble(readText(p, budget));
        expectEnd(p, budget);
        return new Quantity(code, value);
    }

    private static Time readTime(XmlPullParser p, Budget budget) throws SweFormatException, XmlPullParserException,
            IOException {
        allowAttributes(p, "definition");
        expectChild(p, budget, "uom");
        String href = null;
        for (int i = 0; i < p.getAttributeCount(); i++) {
            if (Swe.XLINK_NAMESPACE.equals(p.getAttributeNamespace(i)) && "href".equals(p.getAttributeName(i))) {
                href = p.getAttributeValue(i);
            } else {
                throw malformed("unexpected attribute " + p.getAttributeName(i) + " on Time/uom");
            }
        }
        if (!Swe.ISO_8601_UOM.equals(href)) {
            throw malformed("Time/uom must reference " + Swe.ISO_8601_UOM);
        }
        expectEnd(p, budget);
        expectChild(p, budget, "value");
        allowAttributes(p);
        String text = readText(p, budget);
        expectEnd(p, budget);
        try {
            return new Time(IsoInstant.parse(text));
        } catch (DateTimeParseException e) {
            throw malformed("not an ISO 8601 UTC time stamp: '" + abbreviate(text) + "'");
        }
    }

    private static DataRecord readRecord(XmlPullParser p, Budget budget, int nesting) throws SweFormatException,
            XmlPullParserException, IOException {
        if (nesting >= MAX_NESTING) {
            throw malformed("DataRecords nested deeper than " + MAX_NESTING);
        }
        allowAttributes(p, "definition");
        List<DataRecord.Field> fields = new ArrayList<>();
        List<String> names = new ArrayList<>();
        while (nextChild(p, budget)) {
            requireName(p, "field");
            chargeStartTag(p, budget);
            String fieldName = fieldName(p);
            if (names.contains(fieldName)) {
                throw malformed("duplicate field name " + fieldName);
            }
            names.add(fieldName);
            if (!nextChild(p, budget)) {
                throw malformed("field " + fieldName + " has no component");
            }
            SweComponent c = readComponent(p, budget, nesting + 1);
            expectEnd(p, budget);
            fields.add(new DataRecord.Field(fieldName, c));
        }
        if (fields.isEmpty()) {
            throw malformed("a DataRecord needs at least one field");
        }
        return new DataRecord(fields);
    }

    private static DataArray readArray(XmlPullParser p, Budget budget) throws SweFormatException,
            XmlPullParserException, IOException {
        allowAttributes(p, "definition");
        // elementCount/Count/value
        expectChild(p, budget, "elementCount");
        allowAttributes(p);
        expectChild(p, budget, "Count");
        allowAttributes(p);
        expectChild(p, budget, "value");
        long count = parseLong(readText(p, budget));
        expectEnd(p, budget); // Count
        expectEnd(p, budget); // elementCount
        if (count < 0) {
            throw malformed("negative elementCount");
        }
        // elementType name=.. / DataRecord / field* / (Quantity uom | Count)
        expectChild(p, budget, "elementType");
        String elementName = fieldName(p);
        expectChild(p, budget, "DataRecord");
        allowAttributes(p, "definition");
        List<DataArray.Column> columns = new ArrayList<>();
        while (nextChild(p, budget)) {
            requireName(p, "field");
            chargeStartTag(p, budget);
            String columnName = fieldName(p);
            if (!nextChild(p, budget)) {
                throw malformed("column " + columnName + " has no component");
            }
            requireSwe(p);
            chargeStartTag(p, budget);
            switch (p.getName()) {
                case "Quantity" -> {
                    allowAttributes(p, "definition");
                    expectChild(p, budget, "uom");
                    String code = uomCode(p);
                    expectEnd(p, budget);
                    expectEnd(p, budget);
                    columns.add(DataArray.Column.quantity(columnName, code));
                }
                case "Count" -> {
                    allowAttributes(p, "definition");
                    expectEnd(p, budget);
                    columns.add(DataArray.Column.count(columnName));
                }
                default -> throw malformed("array column " + columnName + " must be a Quantity or a Count");
            }
            expectEnd(p, budget); // field
        }
        if (columns.isEmpty()) {
            throw malformed("array element type without columns");
        }
        expectEnd(p, budget); // elementType
        // encoding / TextEncoding
        expectChild(p, budget, "encoding");
        allowAttributes(p);
        expectChild(p, budget, "TextEncoding");
        readTextEncoding(p);
        expectEnd(p, budget); // TextEncoding
        expectEnd(p, budget); // encoding
        List<double[]> rows = new ArrayList<>();
        if (nextChild(p, budget)) {
            requireName(p, "values");
            chargeStartTag(p, budget);
            allowAttributes(p);
            rows = parseRows(readText(p, budget), columns);
            expectEnd(p, budget); // DataArray
        }
        if (rows.size() != count) {
            throw malformed("elementCount " + count + " but " + rows.size() + " rows");
        }
        return new DataArray(elementName, columns, rows);
    }

    /** Checks the attributes of a {@code TextEncoding}: ControlML's separators only. */
    private static void readTextEncoding(XmlPullParser p) throws SweFormatException {
        String tokenSeparator = null;
        String blockSeparator = null;
        for (int i = 0; i < p.getAttributeCount(); i++) {
            String a = p.getAttributeName(i);
            String v = p.getAttributeValue(i);
            switch (a) {
                case "tokenSeparator" -> tokenSeparator = v;
                case "blockSeparator" -> blockSeparator = v;
                case "decimalSeparator" -> {
                    if (!".".equals(v)) {
                        throw malformed("decimalSeparator must be '.'");
                    }
                }
                case "collapseWhiteSpaces" -> {
                    if (!"true".equals(v)) {
                        throw malformed("collapseWhiteSpaces must be true");
                    }
                }
                default -> throw malformed("unexpected attribute " + a + " on TextEncoding");
            }
        }
        if (!Swe.TOKEN_SEPARATOR.equals(tokenSeparator) || !Swe.BLOCK_SEPARATOR.equals(blockSeparator)) {
            throw malformed("arrays use tokenSeparator=',' and blockSeparator=' '");
        }
    }

    private static List<double[]> parseRows(String values, List<DataArray.Column> columns) throws SweFormatException {
        List<double[]> rows = new ArrayList<>();
        String trimmed = values.strip();
        if (trimmed.isEmpty()) {
            return rows;
        }
        for (String block : trimmed.split("\\s+")) {
            String[] tokens = block.split(",", -1);
            if (tokens.length != columns.size()) {
                throw malformed("row '" + abbreviate(block) + "' has " + tokens.length + " values for "
                        + columns.size() + " columns");
            }
            double[] row = new double[tokens.length];
            for (int i = 0; i < tokens.length; i++) {
                row[i] = columns.get(i).isCount() ? parseLong(tokens[i]) : parseDouble(tokens[i]);
            }
            rows.add(row);
        }
        return rows;
    }

    /** Parses the xs:double lexical space: decimals, exponents, {@code NaN}, {@code INF}, {@code -INF}. */
    public static double parseDouble(String s) throws SweFormatException {
        String t = s.strip();
        switch (t) {
            case "NaN":
                return Double.NaN;
            case "INF", "+INF":
                return Double.POSITIVE_INFINITY;
            case "-INF":
                return Double.NEGATIVE_INFINITY;
            default:
                // no length limit of its own: the payload's size limit bounds every number
                if (!isDecimalDouble(t)) {
                    throw malformed("not an xs:double: '" + abbreviate(t) + "'");
                }
                return Double.parseDouble(t);
        }
    }

    /**
     * The finite part of the xs:double lexical space (XSD 1.0 part 2, 3.2.5.1),
     * {@code [+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?}, scanned by hand (every number of every payload passes here;
     * a regular expression cost more than the parse). Double.parseDouble alone would also take "Infinity",
     * hexadecimal and "1d", which are not xs:double.
     */
    static boolean isDecimalDouble(String t) {
        int n = t.length();
        int i = skipSign(t, 0);
        int end = skipDigits(t, i);
        int mantissaDigits = end - i;
        i = end;
        if (i < n && t.charAt(i) == '.') {
            end = skipDigits(t, i + 1);
            mantissaDigits += end - (i + 1);
            i = end;
        }
        if (mantissaDigits == 0) {
            return false;
        }
        if (i < n && (t.charAt(i) == 'e' || t.charAt(i) == 'E')) {
            i = skipSign(t, i + 1);
            end = skipDigits(t, i);
            if (end == i) {
                return false; // an exponent needs digits
            }
            i = end;
        }
        return i == n;
    }

    /** @return the index after an optional {@code +} or {@code -} at {@code i} */
    private static int skipSign(String t, int i) {
        return i < t.length() && (t.charAt(i) == '+' || t.charAt(i) == '-') ? i + 1 : i;
    }

    /** @return the index after the run of decimal digits starting at {@code i} */
    private static int skipDigits(String t, int i) {
        while (i < t.length() && isDigit(t.charAt(i))) {
            i++;
        }
        return i;
    }

    private static boolean isDigit(char c) {
        return c >= '0' && c <= '9';
    }

    static long parseLong(String s) throws SweFormatException {
        String t = s.strip();
        if (!XS_INTEGER.matcher(t).matches()) {
            throw malformed("not an integer: '" + abbreviate(t) + "'");
        }
        return Long.parseLong(t);
    }

    private static String uomCode(XmlPullParser p) throws SweFormatException {
        String code = null;
        for (int i = 0; i < p.getAttributeCount(); i++) {
            if ("code".equals(p.getAttributeName(i)) && noNamespace(p.getAttributeNamespace(i))) {
                code = p.getAttributeValue(i);
            } else {
                throw malformed("unexpected attribute " + p.getAttributeName(i) + " on uom (use code='...')");
            }
        }
        if (code == null || code.isEmpty() || code.length() > 32 || code.chars().anyMatch(Character::isWhitespace)) {
            throw malformed("uom needs a UCUM code");
        }
        return code;
    }

    private static String readOnlyValue(XmlPullParser p, Budget budget) throws SweFormatException,
            XmlPullParserException, IOException {
        expectChild(p, budget, "value");
        allowAttributes(p);
        String text = readText(p, budget);
        expectEnd(p, budget);
        return text;
    }

    private static String fieldName(XmlPullParser p) throws SweFormatException {
        String name = null;
        for (int i = 0; i < p.getAttributeCount(); i++) {
            if ("name".equals(p.getAttributeName(i)) && noNamespace(p.getAttributeNamespace(i))) {
                name = p.getAttributeValue(i);
            } else {
                throw malformed("unexpected attribute " + p.getAttributeName(i) + " on " + p.getName());
            }
        }
        if (name == null || !NC_NAME.matcher(name).matches()) {
            throw malformed(p.getName() + " needs a name attribute that is an NCName");
        }
        return name;
    }

    /** Text content of the current element, which must have no child elements; leaves the parser on its end tag. */
    private static String readText(XmlPullParser p, Budget budget) throws SweFormatException,
            XmlPullParserException, IOException {
        StringBuilder text = null;
        String single = "";
        while (true) {
            XmlPullParser.Event e = p.next();
            switch (e) {
                case TEXT_CHARACTERS, IGNORABLE_WHITESPACE, ENTITY_REFERENCE -> {
                    String t = p.getText();
                    budget.charge(codePoints(t));
                    if (text == null && single.isEmpty()) {
                        single = t;
                    } else {
                        if (text == null) {
                            text = new StringBuilder(single);
                        }
                        text.append(t);
                    }
                }
                case END_ELEMENT -> {
                    budget.charge(codePoints(p.getName()) + 3);
                    return text == null ? single : text.toString();
                }
                case START_ELEMENT -> throw malformed("element " + p.getName() + " inside a text value");
                case END_DOCUMENT -> throw malformed("document ended inside a value");
                default -> {
                    // comments and processing instructions carry no value
                }
            }
        }
    }

    /**
     * Moves to the next child element of the current element.
     *
     * @return true when positioned on a child's start tag (SWE namespace checked by the caller), false when on the
     *         current element's end tag
     */
    private static boolean nextChild(XmlPullParser p, Budget budget) throws SweFormatException,
            XmlPullParserException, IOException {
        while (true) {
            XmlPullParser.Event e = p.next();
            switch (e) {
                case START_ELEMENT -> {
                    requireSwe(p);
                    return true;
                }
                case END_ELEMENT -> {
                    budget.charge(codePoints(p.getName()) + 3);
                    return false;
                }
                case TEXT_CHARACTERS, IGNORABLE_WHITESPACE, ENTITY_REFERENCE -> {
                    String t = p.getText();
                    budget.charge(codePoints(t));
                    if (!t.isBlank()) {
                        throw malformed("text '" + abbreviate(t.strip()) + "' where an element belongs");
                    }
                }
                case END_DOCUMENT -> throw malformed("document ended inside an element");
                default -> {
                    // whitespace, comments, processing instructions
                }
            }
        }
    }

    private static void expectChild(XmlPullParser p, Budget budget, String name) throws SweFormatException,
            XmlPullParserException, IOException {
        if (!nextChild(p, budget)) {
            throw malformed("missing element " + name);
        }
        requireName(p, name);
        chargeStartTag(p, budget);
    }

    private static void expectEnd(XmlPullParser p, Budget budget) throws SweFormatException, XmlPullParserException,
            IOException {
        if (nextChild(p, budget)) {
            throw malformed("unexpected element " + p.getName());
        }
    }

    private static void requireName(XmlPullParser p, String name) throws SweFormatException {
        if (!name.equals(p.getName())) {
            throw malformed("expected element " + name + ", found " + p.getName());
        }
    }

    private static void requireSwe(XmlPullParser p) throws SweFormatException {
        if (!Swe.NAMESPACE.equals(p.getNamespace())) {
            throw malformed("element " + p.getName() + " in namespace '" + p.getNamespace()
                    + "' where a SWE Common 2.0 element belongs");
        }
    }

    private static void allowAttributes(XmlPullParser p, String... allowed) throws SweFormatException {
        outer: for (int i = 0; i < p.getAttributeCount(); i++) {
            String a = p.getAttributeName(i);
            if (noNamespace(p.getAttributeNamespace(i))) {
                for (String ok : allowed) {
                    if (ok.equals(a)) {
                        continue outer;
                    }
                }
            }
            throw malformed("unexpected attribute " + a + " on " + p.getName());
        }
    }

    private static void chargeStartTag(XmlPullParser p, Budget budget) throws SweFormatException {
        int n = codePoints(p.getName()) + 2;
        for (int i = 0; i < p.getAttributeCount(); i++) {
            n += codePoints(p.getAttributeName(i)) + codePoints(p.getAttributeValue(i)) + 4;
        }
        budget.charge(n);
    }

    /**
     * @return the number of Unicode code points of {@code s}: the unit of the payload size (docs/CONTROLML.md
     *         section 1), which a peer in any language counts the same way (UTF-16 units would not be)
     */
    static int codePoints(String s) {
        int n = s.length();
        for (int i = 0; i < s.length(); i++) {
            if (Character.isLowSurrogate(s.charAt(i)) && i > 0 && Character.isHighSurrogate(s.charAt(i - 1))) {
                n--;
            }
        }
        return n;
    }

    private static SweFormatException malformed(String message) {
        return new SweFormatException(SweFormatException.Problem.MALFORMED, message);
    }

    /** @return true for an attribute without namespace (parsers report it as null or as the empty string) */
    public static boolean noNamespace(String namespace) {
        return namespace == null || namespace.isEmpty();
    }

    static String abbreviate(String s) {
        return s.length() <= 40 ? s : s.substring(0, 40) + "...";
    }

    // ------------------------------------------------------------------------------------------------ writing

    /**
     * Writes a component in canonical form; the outermost element declares the SWE namespace as default namespace.
     *
     * @param component the component
     * @param out       receives the XML
     */
    public static void write(SweComponent component, StringBuilder out) {
        write(component, out, true);
    }

    /**
     * Writes a record in the text form: a {@code DataStream} whose {@code elementType} refers to {@code href} and whose
     * {@code values} hold the record's tokens.
     *
     * @param template the structure {@code href} names; {@code record} must {@link RecordTemplate#fits fit} it
     */
    public static void writeStream(String href, RecordTemplate template, SweComponent record, StringBuilder out) {
        out.append("<DataStream xmlns='").append(Swe.NAMESPACE).append("' xmlns:xlink='").append(Swe.XLINK_NAMESPACE)
                .append("'><elementType name='value' xlink:href='");
        escape(href, out);
        out.append("'/><encoding><TextEncoding tokenSeparator='").append(Swe.TOKEN_SEPARATOR).append(
                "' blockSeparator='").append(Swe.BLOCK_SEPARATOR).append("'/></encoding><values>");
        template.writeValues(record, out);
        out.append("</values></DataStream>");
    }

    /** @return the canonical XML of a component */
    public static String toXml(SweComponent component) {
        StringBuilder sb = new StringBuilder(256);
        write(component, sb, true);
        return sb.toString();
    }

    private static void write(SweComponent c, StringBuilder out, boolean root) {
        out.append('<').append(c.elementName());
        if (root) {
            out.append(" xmlns='").append(Swe.NAMESPACE).append('\'');
        }
        out.append('>');
        switch (c) {
            case Quantity q -> {
                out.append("<uom code='");
                escape(q.uom(), out);
                out.append("'/><value>").append(formatDouble(q.value())).append("</value>");
            }
            case Count n -> out.append("<value>").append(n.value()).append("</value>");
            case Time t -> {
                out.append("<uom xmlns:xlink='").append(Swe.XLINK_NAMESPACE).append("' xlink:href='").append(
                        Swe.ISO_8601_UOM).append("'/><value>");
                IsoInstant.format(t.value(), out);
                out.append("</value>");
            }
            case Text t -> {
                out.append("<value>");
                escape(t.value(), out);
                out.append("</value>");
            }
            case Category t -> {
                out.append("<value>");
                escape(t.value(), out);
                out.append("</value>");
            }
            case SweBoolean b -> out.append("<value>").append(b.value()).append("</value>");
            case DataRecord r -> {
                for (DataRecord.Field f : r.fields()) {
                    out.append("<field name='");
                    escape(f.name(), out);
                    out.append("'>");
                    write(f.component(), out, false);
                    out.append("</field>");
                }
            }
            case DataArray a -> writeArray(a, out);
        }
        out.append("</").append(c.elementName()).append('>');
    }

    private static void writeArray(DataArray a, StringBuilder out) {
        out.append("<elementCount><Count><value>").append(a.size()).append("</value></Count></elementCount>");
        out.append("<elementType name='");
        escape(a.rowName(), out);
        out.append("'><DataRecord>");
        for (DataArray.Column col : a.columns()) {
            out.append("<field name='");
            escape(col.name(), out);
            out.append("'>");
            if (col.isCount()) {
                out.append("<Count/>");
            } else {
                out.append("<Quantity><uom code='");
                escape(col.uom(), out);
                out.append("'/></Quantity>");
            }
            out.append("</field>");
        }
        out.append("</DataRecord></elementType>");
        out.append("<encoding><TextEncoding tokenSeparator='").append(Swe.TOKEN_SEPARATOR).append(
                "' blockSeparator='").append(Swe.BLOCK_SEPARATOR).append("'/></encoding>");
        out.append("<values>");
        int columns = a.columns().size();
        for (int r = 0; r < a.size(); r++) {
            if (r > 0) {
                out.append(Swe.BLOCK_SEPARATOR);
            }
            for (int c = 0; c < columns; c++) {
                if (c > 0) {
                    out.append(Swe.TOKEN_SEPARATOR);
                }
                double v = a.value(r, c);
                if (a.columns().get(c).isCount()) {
                    out.append((long) v);
                } else {
                    out.append(formatDouble(v));
                }
            }
        }
        out.append("</values>");
    }

    /** @return the xs:double lexical form of a value ({@code NaN}, {@code INF}, {@code -INF} for non-finite) */
    public static String formatDouble(double v) {
        if (Double.isNaN(v)) {
            return "NaN";
        }
        if (Double.isInfinite(v)) {
            return v > 0 ? "INF" : "-INF";
        }
        return Double.toString(v);
    }

    /** Escapes text for element content and single-quoted attribute values. */
    public static void escape(CharSequence s, StringBuilder out) {
        for (int i = 0; i < s.length(); i++) {
            char ch = s.charAt(i);
            switch (ch) {
                case '<' -> out.append("&lt;");
                case '>' -> out.append("&gt;");
                case '&' -> out.append("&amp;");
                case '\'' -> out.append("&apos;");
                case '"' -> out.append("&quot;");
                default -> out.append(ch);
            }
        }
    }
}
