package sabot.identity;

import java.io.StringReader;
import java.util.ArrayList;
import java.util.List;

import javax.xml.XMLConstants;
import javax.xml.parsers.DocumentBuilder;
import javax.xml.parsers.DocumentBuilderFactory;

import org.w3c.dom.Document;
import org.w3c.dom.Element;
import org.w3c.dom.Node;
import org.xml.sax.InputSource;

/**
 * Writes and reads the QR-Code inventory document. The writer emits the compact form (no whitespace, single quotes,
 * no DOCTYPE: the DTD is {@code docs/IDENTITY.md}'s, identified by the root's {@code VERSION}); the reader checks
 * the structure and the ELECTRONIC section's {@code HASH}.
 */
public final class InventoryXml {

    private InventoryXml() {
    }

    /** @return the document as compact XML */
    public static String write(Inventory inv) {
        StringBuilder sb = new StringBuilder(1024);
        sb.append("<QRCODE VERSION='").append(inv.version()).append("' UID='");
        esc(inv.uid(), sb).append("'><MECHANIC MODEL='");
        esc(inv.mechanic().model(), sb).append("'>");
        for (Inventory.Part p : inv.mechanic().parts()) {
            sb.append("<PART NAME='");
            esc(p.name(), sb).append("' VALUE='");
            esc(p.value(), sb).append("'/>");
        }
        sb.append("</MECHANIC><ELECTRONIC HASH='").append(inv.electronicHash()).append("'>");
        for (Inventory.Board b : inv.boards()) {
            sb.append("<BOARD NAME='");
            esc(b.name(), sb).append("' CPU='");
            esc(b.cpu(), sb).append("'>");
            if (b.bsp() != null) {
                item("BSP", b.bsp(), sb);
            }
            b.packages().forEach(i -> item("PACKAGE", i, sb));
            b.applications().forEach(i -> item("APPLICATION", i, sb));
            b.libraries().forEach(i -> item("LIBRARY", i, sb));
            sb.append("</BOARD>");
        }
        sb.append("</ELECTRONIC>");
        for (Inventory.SpecialDevice d : inv.specialDevices()) {
            sb.append("<SPECIAL_DEVICE NAME='");
            esc(d.name(), sb).append("' MODEL='");
            esc(d.model(), sb).append("' BUS='");
            esc(d.bus(), sb).append("' ADDRESS='");
            esc(d.address(), sb).append("'/>");
        }
        return sb.append("</QRCODE>").toString();
    }

    private static void item(String kind, Inventory.Item i, StringBuilder sb) {
        sb.append('<').append(kind).append(" NAME='");
        esc(i.name(), sb).append("' VERSION='");
        esc(i.version(), sb).append("'/>");
    }

    private static StringBuilder esc(String s, StringBuilder sb) {
        for (int i = 0; i < s.length(); i++) {
            char c = s.charAt(i);
            switch (c) {
                case '<' -> sb.append("&lt;");
                case '&' -> sb.append("&amp;");
                case '\'' -> sb.append("&apos;");
                case '"' -> sb.append("&quot;");
                default -> sb.append(c);
            }
        }
        return sb;
    }

    /** @return the inventory of a document, or why it is not one */
    public static IdentityResult<Inventory> read(String xml) {
        try {
            DocumentBuilderFactory f = DocumentBuilderFactory.newInstance();
            f.setFeature(XMLConstants.FEATURE_SECURE_PROCESSING, true);
            f.setFeature("http://apache.org/xml/features/disallow-doctype-decl", true);
            f.setExpandEntityReferences(false);
            DocumentBuilder b = f.newDocumentBuilder();
            b.setErrorHandler(null);
            Document doc = b.parse(new InputSource(new StringReader(xml)));
            Element root = doc.getDocumentElement();
            require(root, "QRCODE");
            List<Element> top = children(root);
            if (top.size() < 2) {
                return notInventory("QRCODE needs MECHANIC and ELECTRONIC");
            }
            Element mech = top.get(0);
            require(mech, "MECHANIC");
            List<Inventory.Part> parts = new ArrayList<>();
            for (Element p : children(mech)) {
                require(p, "PART");
                parts.add(new Inventory.Part(attr(p, "NAME"), attr(p, "VALUE")));
            }
            Element el = top.get(1);
            require(el, "ELECTRONIC");
            List<Inventory.Board> boards = new ArrayList<>();
            for (Element be : children(el)) {
                require(be, "BOARD");
                Inventory.Item bsp = null;
                List<Inventory.Item> packages = new ArrayList<>();
                List<Inventory.Item> apps = new ArrayList<>();
                List<Inventory.Item> libs = new ArrayList<>();
                for (Element ie : children(be)) {
                    Inventory.Item item = new Inventory.Item(attr(ie, "NAME"), attr(ie, "VERSION"));
                    switch (ie.getTagName()) {
                        case "BSP" -> bsp = item;
                        case "PACKAGE" -> packages.add(item);
                        case "APPLICATION" -> apps.add(item);
                        case "LIBRARY" -> libs.add(item);
                        default -> throw new IllegalArgumentException("unexpected " + ie.getTagName() + " in BOARD");
                    }
                }
                boards.add(new Inventory.Board(attr(be, "NAME"), attr(be, "CPU"), bsp, packages, apps, libs));
            }
            List<Inventory.SpecialDevice> devices = new ArrayList<>();
            for (Element d : top.subList(2, top.size())) {
                require(d, "SPECIAL_DEVICE");
                devices.add(new Inventory.SpecialDevice(attr(d, "NAME"), attr(d, "MODEL"), attr(d, "BUS"), attr(d,
                        "ADDRESS")));
            }
            Inventory inv = new Inventory(Integer.parseInt(attr(root, "VERSION")), attr(root, "UID"),
                    new Inventory.Mechanic(attr(mech, "MODEL"), parts), boards, devices);
            String hash = attr(el, "HASH");
            if (!hash.equals(inv.electronicHash())) {
                return notInventory("ELECTRONIC HASH does not match its content");
            }
            return new IdentityResult.Ok<>(inv);
        } catch (Exception e) {
            return notInventory(e.getMessage());
        }
    }

    private static IdentityResult<Inventory> notInventory(String why) {
        return IdentityResult.err(IdentityResult.Problem.NOT_AN_INVENTORY, "not an inventory document: " + why);
    }

    private static void require(Element e, String name) {
        if (!name.equals(e.getTagName())) {
            throw new IllegalArgumentException("expected " + name + ", found " + e.getTagName());
        }
    }

    private static String attr(Element e, String name) {
        if (!e.hasAttribute(name)) {
            throw new IllegalArgumentException(e.getTagName() + " needs " + name);
        }
        return e.getAttribute(name);
    }

    private static List<Element> children(Element e) {
        List<Element> out = new ArrayList<>();
        for (Node n = e.getFirstChild(); n != null; n = n.getNextSibling()) {
            if (n instanceof Element c) {
                out.add(c);
            } else if (n.getNodeType() == Node.TEXT_NODE && !n.getTextContent().isBlank()) {
                throw new IllegalArgumentException("text inside " + e.getTagName());
            }
        }
        return out;
    }
}
