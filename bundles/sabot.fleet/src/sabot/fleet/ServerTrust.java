package sabot.fleet;

import java.io.IOException;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.GeneralSecurityException;
import java.security.KeyStore;
import java.security.MessageDigest;
import java.security.cert.CertPathValidatorException;
import java.security.cert.Certificate;
import java.security.cert.CertificateExpiredException;
import java.security.cert.CertificateFactory;
import java.security.cert.CertificateNotYetValidException;
import java.security.cert.X509Certificate;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.List;
import java.util.Locale;

import javax.net.ssl.SSLHandshakeException;
import javax.net.ssl.TrustManager;
import javax.net.ssl.TrustManagerFactory;
import javax.net.ssl.X509TrustManager;

/**
 * Whom a Sabot client trusts to be its XMPP server: the certificates of a lab CA read from a PEM file (the one
 * {@code ./sabot xmpp start} makes, {@code DIR/ca/ca.pem}, or a lab's own), or, without a file, the JVM's default trust
 * store (a server with a publicly signed certificate). Every connection requires TLS and checks that the server's
 * certificate names its XMPP domain; a failure is told in one line ({@link #explain}), never by falling back to a
 * plain or unchecked connection.
 */
public final class ServerTrust {

    private final Path caFile;
    private final List<X509Certificate> authorities;
    private final X509TrustManager trustManager;

    private ServerTrust(Path caFile, List<X509Certificate> authorities, X509TrustManager trustManager) {
        this.caFile = caFile;
        this.authorities = List.copyOf(authorities);
        this.trustManager = trustManager;
    }

    /** @return the X.509 trust manager of {@code store} (null: the JVM's default trust store) */
    private static X509TrustManager trustManager(KeyStore store) throws GeneralSecurityException {
        TrustManagerFactory tmf = TrustManagerFactory.getInstance(TrustManagerFactory.getDefaultAlgorithm());
        tmf.init(store);
        for (TrustManager tm : tmf.getTrustManagers()) {
            if (tm instanceof X509TrustManager x509) {
                return x509;
            }
        }
        throw new GeneralSecurityException("no X.509 trust manager in " + tmf.getAlgorithm());
    }

    /**
     * @param caFile a PEM file of one or more CA certificates
     * @return trust in those certificates only (not the JVM's default store)
     * @throws IOException the file cannot be read, or holds no certificate, or one that is not a CA's
     */
    public static ServerTrust labCa(Path caFile) throws IOException {
        List<X509Certificate> certificates = new ArrayList<>();
        try (InputStream in = Files.newInputStream(caFile)) {
            for (Certificate c : CertificateFactory.getInstance("X.509").generateCertificates(in)) {
                certificates.add((X509Certificate) c);
            }
        } catch (GeneralSecurityException e) {
            throw new IOException(caFile + ": not a PEM certificate file (" + e.getMessage() + ")", e);
        }
        if (certificates.isEmpty()) {
            throw new IOException(caFile + ": no certificate in it");
        }
        for (X509Certificate c : certificates) {
            if (c.getBasicConstraints() < 0) {
                throw new IOException(caFile + ": the certificate of " + c.getSubjectX500Principal().getName()
                        + " is not a CA's (basic constraints)");
            }
        }
        try {
            KeyStore store = KeyStore.getInstance(KeyStore.getDefaultType());
            store.load(null, null);
            for (int i = 0; i < certificates.size(); i++) {
                store.setCertificateEntry("lab-ca-" + i, certificates.get(i));
            }
            return new ServerTrust(caFile, certificates, trustManager(store));
        } catch (GeneralSecurityException e) {
            throw new IOException(caFile + ": " + e.getMessage(), e);
        }
    }

    /** @return trust in the JVM's default trust store (publicly signed server certificates) */
    public static ServerTrust jvmDefault() {
        try {
            return new ServerTrust(null, List.of(), trustManager(null));
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("the JVM has no default TLS context: " + e.getMessage(), e);
        }
    }

    /**
     * @param caFile a PEM file, or null or empty for the JVM's default trust store
     * @return {@link #labCa} or {@link #jvmDefault}
     */
    public static ServerTrust of(String caFile) throws IOException {
        return caFile == null || caFile.isBlank() ? jvmDefault() : labCa(Path.of(caFile.strip()));
    }

    /** @return the trust manager that checks the server's certificate chain */
    public X509TrustManager trustManager() {
        return trustManager;
    }

    /** @return the CA file, or null for the JVM's default trust store */
    public Path caFile() {
        return caFile;
    }

    /** @return the SHA-256 fingerprint of each trusted CA certificate, {@code AB:CD:...}; empty for the JVM's store */
    public List<String> fingerprints() {
        List<String> out = new ArrayList<>();
        for (X509Certificate c : authorities) {
            out.add(fingerprint(c));
        }
        return out;
    }

    /** @return the SHA-256 fingerprint of {@code certificate}'s DER encoding, upper-case hex pairs joined by ':' */
    public static String fingerprint(X509Certificate certificate) {
        try {
            byte[] digest = MessageDigest.getInstance("SHA-256").digest(certificate.getEncoded());
            return HexFormat.ofDelimiter(":").withUpperCase().formatHex(digest);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException(e);
        }
    }

    /** @return what is trusted, for a log line: the file and its fingerprint(s), or the JVM's default store */
    public String describe() {
        return caFile == null ? "the JVM's default trust store" : "the CA of " + caFile + " (SHA-256 "
                + String.join(", ", fingerprints()) + ")";
    }

    /**
     * @param failure what a connection attempt threw
     * @param domain  the XMPP domain the certificate had to name
     * @return one line saying why the server's certificate was refused, or null when the failure is not about it
     */
    public String explain(Throwable failure, String domain) {
        for (Throwable t = failure; t != null; t = t.getCause()) {
            if (t instanceof CertificateExpiredException e) {
                return "the certificate for " + domain + " has expired (" + e.getMessage() + ")";
            }
            if (t instanceof CertificateNotYetValidException e) {
                return "the certificate for " + domain + " is not valid yet (" + e.getMessage() + ")";
            }
            if (t instanceof CertPathValidatorException || t instanceof java.security.cert.CertPathBuilderException
                    || t instanceof SSLHandshakeException && String.valueOf(t.getMessage()).contains("PKIX")) {
                if (hasCause(t, CertificateExpiredException.class)) {
                    continue;
                }
                return "the certificate for " + domain + " is not signed by " + describe();
            }
            if (t instanceof java.security.cert.CertificateException && String.valueOf(t.getMessage()).toLowerCase(
                    Locale.ROOT).contains("hostname verification")) {
                return "the server's certificate does not name " + domain + " (trusted: " + describe() + ")";
            }
        }
        return null;
    }

    private static boolean hasCause(Throwable t, Class<? extends Throwable> type) {
        for (Throwable c = t; c != null; c = c.getCause()) {
            if (type.isInstance(c)) {
                return true;
            }
        }
        return false;
    }

    @Override
    public String toString() {
        return "ServerTrust[" + describe() + "]";
    }
}
