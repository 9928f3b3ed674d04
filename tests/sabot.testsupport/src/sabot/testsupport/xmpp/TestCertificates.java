package sabot.testsupport.xmpp;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;

/** Certificates for tests, made by openssl the way {@code product/bin/sabot-xmpp} makes the lab CA. */
public final class TestCertificates {

    private TestCertificates() {
    }

    /**
     * Makes a CA certificate (P-256, one day) that signs nothing of any server: a client that trusts it trusts no
     * server's certificate.
     *
     * @return its PEM file in {@code dir} ({@code NAME.pem}, the key beside it)
     */
    public static Path anotherCa(Path dir, String name) throws IOException, InterruptedException {
        Path pem = dir.resolve(name + ".pem");
        Process openssl = new ProcessBuilder("openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt",
                "ec_paramgen_curve:prime256v1", "-nodes", "-days", "1", "-subj", "/CN=" + name, "-addext",
                "basicConstraints=critical,CA:TRUE", "-keyout", dir.resolve(name + ".key").toString(), "-out",
                pem.toString()).redirectErrorStream(true).start();
        String output = new String(openssl.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        if (openssl.waitFor() != 0) {
            throw new IOException("openssl could not make a CA: " + output);
        }
        return pem;
    }
}
