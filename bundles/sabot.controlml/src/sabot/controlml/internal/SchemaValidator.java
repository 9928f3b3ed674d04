package sabot.controlml.internal;

import java.io.IOException;
import java.io.InputStream;
import java.io.Reader;
import java.io.StringReader;
import java.io.UncheckedIOException;
import java.net.URI;
import java.net.URL;

import javax.xml.XMLConstants;
import javax.xml.transform.stream.StreamSource;
import javax.xml.validation.Schema;
import javax.xml.validation.SchemaFactory;
import javax.xml.validation.Validator;

import org.osgi.framework.Bundle;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.namespace.BundleNamespace;
import org.osgi.framework.wiring.BundleWire;
import org.osgi.framework.wiring.BundleWiring;
import org.w3c.dom.ls.LSInput;
import org.w3c.dom.ls.LSResourceResolver;
import org.xml.sax.SAXException;

import sabot.controlml.ControlMlElement;

/**
 * Validates ControlML elements against {@code controlml.xsd} (this bundle's {@code schema/}, the same file as
 * {@code docs/controlml.xsd}), which imports the OGC SWE Common 2.0 schema.
 * <p>
 * The OGC and W3C schemas come from the Maven artifacts {@code org.jvnet.ogc:ogc-schemas} and
 * {@code org.hisrc.w3c:w3c-schemas}. Their folders (e.g. {@code ogc/sweCommon/2.0}) are not valid package names, so
 * in OSGi they are read with {@link Bundle#getEntry} from the bundles this bundle requires; on a plain class path
 * (the benchmark) with the class loader. The {@code http://schemas.opengis.net/} and {@code http://www.w3.org/}
 * locations are mapped onto those copies: nothing is ever fetched from the network.
 */
public final class SchemaValidator {

    private static final String OGC = "http://schemas.opengis.net/";
    private static final String W3C = "http://www.w3.org/";

    private static volatile SchemaValidator shared;

    private final Schema schema;
    private final ThreadLocal<Validator> validators;

    private SchemaValidator() {
        try {
            SchemaFactory factory = SchemaFactory.newInstance(XMLConstants.W3C_XML_SCHEMA_NS_URI);
            factory.setResourceResolver(new Resolver());
            URL main = SchemaValidator.class.getResource("/schema/controlml.xsd");
            if (main == null) {
                throw new IllegalStateException("schema/controlml.xsd missing from sabot.controlml");
            }
            try (InputStream in = main.openStream()) {
                StreamSource source = new StreamSource(in, "urn:sabot:controlml:1:xsd");
                schema = factory.newSchema(source);
            }
        } catch (SAXException e) {
            throw new IllegalStateException("controlml.xsd does not compile: " + e.getMessage(), e);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
        validators = ThreadLocal.withInitial(schema::newValidator);
    }

    /** @return the process-wide validator (compiling the schemas once takes a few hundred milliseconds) */
    public static SchemaValidator shared() {
        SchemaValidator s = shared;
        if (s == null) {
            synchronized (SchemaValidator.class) {
                s = shared;
                if (s == null) {
                    s = new SchemaValidator();
                    shared = s;
                }
            }
        }
        return s;
    }

    /** @return the compiled schema */
    public Schema schema() {
        return schema;
    }

    /** @return null when the element is valid, else the validator's message */
    public String problemWith(ControlMlElement element) {
        return problemWith(element.toXML(org.jivesoftware.smack.packet.XmlEnvironment.EMPTY).toString());
    }

    /** @return null when the XML document is valid, else the validator's message */
    public String problemWith(String xml) {
        try {
            validators.get().validate(new StreamSource(new StringReader(xml)));
            return null;
        } catch (SAXException e) {
            return "not valid against controlml.xsd: " + e.getMessage();
        } catch (IOException e) {
            return "unreadable: " + e.getMessage();
        }
    }

    /** Finds a resource of the schema artifacts, in OSGi or on a class path. */
    static URL locate(String path) {
        URL url = SchemaValidator.class.getClassLoader().getResource(path);
        if (url != null) {
            return url;
        }
        try {
            Bundle self = FrameworkUtil.getBundle(SchemaValidator.class);
            BundleWiring wiring = self == null ? null : self.adapt(BundleWiring.class);
            if (wiring != null) {
                for (BundleWire wire : wiring.getRequiredWires(BundleNamespace.BUNDLE_NAMESPACE)) {
                    URL entry = wire.getProvider().getBundle().getEntry(path);
                    if (entry != null) {
                        return entry;
                    }
                }
            }
        } catch (LinkageError notOsgi) {
            // no OSGi framework on the class path: the class loader lookup above was the only way
        }
        return null;
    }

    private static final class Resolver implements LSResourceResolver {
        @Override
        public LSInput resolveResource(String type, String namespaceURI, String publicId, String systemId,
                String baseURI) {
            if (systemId == null) {
                return null;
            }
            String absolute = baseURI == null || baseURI.startsWith("urn:") ? systemId : URI.create(baseURI).resolve(
                    systemId).toString();
            String path;
            if (absolute.startsWith(OGC)) {
                path = "ogc/" + absolute.substring(OGC.length());
            } else if (absolute.startsWith(W3C)) {
                path = "w3c/" + absolute.substring(W3C.length());
            } else {
                throw new IllegalStateException("schema " + absolute + " is not packaged (no network access)");
            }
            URL url = locate(path);
            if (url == null) {
                throw new IllegalStateException("schema " + absolute + " not found as " + path
                        + " (ogc-schemas / w3c-schemas missing?)");
            }
            try {
                return new Input(publicId, absolute, url.openStream());
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
        }
    }

    private record Input(String publicId, String systemId, InputStream stream) implements LSInput {
        @Override
        public Reader getCharacterStream() {
            return null;
        }

        @Override
        public void setCharacterStream(Reader characterStream) {
        }

        @Override
        public InputStream getByteStream() {
            return stream;
        }

        @Override
        public void setByteStream(InputStream byteStream) {
        }

        @Override
        public String getStringData() {
            return null;
        }

        @Override
        public void setStringData(String stringData) {
        }

        @Override
        public String getSystemId() {
            return systemId;
        }

        @Override
        public void setSystemId(String systemId) {
        }

        @Override
        public String getPublicId() {
            return publicId;
        }

        @Override
        public void setPublicId(String publicId) {
        }

        @Override
        public String getBaseURI() {
            return systemId;
        }

        @Override
        public void setBaseURI(String baseURI) {
        }

        @Override
        public String getEncoding() {
            return null;
        }

        @Override
        public void setEncoding(String encoding) {
        }

        @Override
        public boolean getCertifiedText() {
            return false;
        }

        @Override
        public void setCertifiedText(boolean certifiedText) {
        }
    }
}
