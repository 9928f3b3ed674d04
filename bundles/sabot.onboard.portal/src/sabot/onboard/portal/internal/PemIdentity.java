package sabot.onboard.portal.internal;

import java.io.ByteArrayInputStream;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.security.GeneralSecurityException;
import java.security.KeyFactory;
import java.security.KeyStore;
import java.security.PrivateKey;
import java.security.cert.Certificate;
import java.security.cert.CertificateFactory;
import java.security.spec.PKCS8EncodedKeySpec;
import java.util.ArrayList;
import java.util.Base64;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import javax.net.ssl.KeyManagerFactory;
import javax.net.ssl.SSLContext;

/**
 * The page's TLS identity from PEM files as the lab CA writes them ({@code openssl req -newkey ec -nodes}: the
 * certificate, and the key as an unencrypted PKCS #8 {@code PRIVATE KEY}).
 */
final class PemIdentity {

    /** The two files. */
    record Files(Path certificate, Path key) {
    }

    /** The key's alias in {@link #keyStore}. */
    static final String ALIAS = "portal";

    private static final Pattern BLOCK = Pattern.compile("-----BEGIN ([A-Z ]+)-----([A-Za-z0-9+/=\\s]+)-----END \\1-----");

    private PemIdentity() {
    }

    /** @return a TLS context serving the certificate (and the chain after it in the file) with the key */
    static SSLContext load(Files files) throws IOException, GeneralSecurityException {
        char[] password = new char[0];
        KeyManagerFactory kmf = KeyManagerFactory.getInstance(KeyManagerFactory.getDefaultAlgorithm());
        kmf.init(keyStore(files, password), password);
        SSLContext context = SSLContext.getInstance("TLS");
        context.init(kmf.getKeyManagers(), null, null);
        return context;
    }

    /**
     * @return a PKCS #12 key store holding the key under the alias {@value #ALIAS} with the certificate and the chain
     *         after it in the file, the key and the store protected by {@code password}
     */
    static KeyStore keyStore(Files files, char[] password) throws IOException, GeneralSecurityException {
        List<Certificate> chain = new ArrayList<>();
        CertificateFactory x509 = CertificateFactory.getInstance("X.509");
        for (byte[] der : blocks(files.certificate(), "CERTIFICATE")) {
            chain.add(x509.generateCertificate(new ByteArrayInputStream(der)));
        }
        if (chain.isEmpty()) {
            throw new GeneralSecurityException(files.certificate() + " holds no PEM CERTIFICATE");
        }
        List<byte[]> keys = blocks(files.key(), "PRIVATE KEY");
        if (keys.size() != 1) {
            throw new GeneralSecurityException(files.key() + " holds no unencrypted PKCS #8 PRIVATE KEY (or several)");
        }
        String algorithm = chain.get(0).getPublicKey().getAlgorithm();
        PrivateKey key = KeyFactory.getInstance(algorithm).generatePrivate(new PKCS8EncodedKeySpec(keys.get(0)));
        KeyStore store = KeyStore.getInstance("PKCS12");
        store.load(null, null);
        store.setKeyEntry(ALIAS, key, password, chain.toArray(Certificate[]::new));
        return store;
    }

    private static List<byte[]> blocks(Path file, String type) throws IOException {
        String text = java.nio.file.Files.readString(file, StandardCharsets.US_ASCII);
        List<byte[]> blocks = new ArrayList<>();
        Matcher m = BLOCK.matcher(text);
        while (m.find()) {
            if (m.group(1).equals(type)) {
                blocks.add(Base64.getMimeDecoder().decode(m.group(2)));
            }
        }
        return blocks;
    }
}
