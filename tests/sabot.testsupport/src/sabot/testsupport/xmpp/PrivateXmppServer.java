package sabot.testsupport.xmpp;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.io.UncheckedIOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.UUID;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.ConnectionConfiguration.SecurityMode;
import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.tcp.XMPPTCPConnectionConfiguration;
import org.jivesoftware.smackx.iqregister.AccountManager;
import org.junit.jupiter.api.extension.AfterAllCallback;
import org.junit.jupiter.api.extension.BeforeAllCallback;
import org.junit.jupiter.api.extension.ExtensionContext;
import org.jxmpp.jid.DomainBareJid;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.jid.parts.Localpart;

import sabot.fleet.NoDelaySocketFactory;

/**
 * A private XMPP server (Prosody or ejabberd) on a free loopback port, with its own configuration and state
 * directory, for one test class. Real server, real sockets: nothing is mocked.
 *
 * <pre>
 * &#64;RegisterExtension
 * static PrivateXmppServer xmpp = PrivateXmppServer.prosody();
 * ...
 * XMPPTCPConnection alice = xmpp.login("alice");   // account created by in-band registration on first use
 * </pre>
 *
 * The server's configuration is the project's own ({@code product/xmpp/}), the same one {@code ./sabot xmpp} uses;
 * the MAM archive is kept in memory. The system-wide server is never touched: every start passes the private
 * configuration. Usable outside JUnit through {@link #start()} and {@link #close()}.
 */
public final class PrivateXmppServer implements BeforeAllCallback, AfterAllCallback, AutoCloseable {

    /** The server implementations the fixture can run. */
    public enum Kind {
        PROSODY("/usr/bin/prosody", "prosody"), EJABBERD("/usr/sbin/ejabberdctl", "ejabberd");

        final String executable;
        final String debianPackage;

        Kind(String executable, String debianPackage) {
            this.executable = executable;
            this.debianPackage = debianPackage;
        }
    }

    /** The first virtual host. */
    public static final String DOMAIN = "sabot.local";
    /** The second virtual host, for cross-domain exchanges. */
    public static final String SECOND_DOMAIN = "sabot2.local";
    /** Password given to accounts that the fixture creates on demand. */
    public static final String DEFAULT_PASSWORD = "sabot-test-pw";

    private static final Duration READY_TIMEOUT = Duration.ofSeconds(60);
    private static final Duration STOP_GRACE = Duration.ofSeconds(3);

    private final Kind kind;
    private final List<XMPPTCPConnection> connections = new ArrayList<>();
    private Process process;
    private Path runDir;
    private int port;
    private Duration startupTime;
    private Thread shutdownHook;

    private PrivateXmppServer(Kind kind) {
        this.kind = Objects.requireNonNull(kind);
    }

    /** @return a fixture for a private Prosody (about 0.1 s to ready here) */
    public static PrivateXmppServer prosody() {
        return new PrivateXmppServer(Kind.PROSODY);
    }

    /** @return a fixture for a private ejabberd (about 1 s to ready here) */
    public static PrivateXmppServer ejabberd() {
        return new PrivateXmppServer(Kind.EJABBERD);
    }

    /** @return a fixture for the given server kind */
    public static PrivateXmppServer of(Kind kind) {
        return new PrivateXmppServer(kind);
    }

    @Override
    public void beforeAll(ExtensionContext context) throws Exception {
        start();
    }

    @Override
    public void afterAll(ExtensionContext context) {
        close();
    }

    /** Starts the server and waits until it answers a client stream header with its stream features. */
    public synchronized PrivateXmppServer start() throws IOException, InterruptedException {
        if (process != null) {
            return this;
        }
        if (!Files.isExecutable(Paths.get(kind.executable))) {
            throw new IllegalStateException(kind.executable + " not found: install it with 'apt-get install -y "
                    + kind.debianPackage + "' (or run ./sabot test as root, which installs it)");
        }
        Path root = repositoryRoot();
        runDir = root.resolve("target/xmpp-run/" + kind.name().toLowerCase() + "-" + UUID.randomUUID().toString()
                .substring(0, 8)).toAbsolutePath();
        Files.createDirectories(runDir.resolve("data"));
        Files.createDirectories(runDir.resolve("certs"));
        port = freeLoopbackPort();
        long t0 = System.nanoTime();
        process = switch (kind) {
            case PROSODY -> startProsody(root);
            case EJABBERD -> startEjabberd(root);
        };
        shutdownHook = new Thread(this::stopProcess, "stop-private-" + kind.debianPackage);
        Runtime.getRuntime().addShutdownHook(shutdownHook);
        awaitReady();
        startupTime = Duration.ofNanos(System.nanoTime() - t0);
        System.out.printf("[xmpp] private %s pid %d ready on 127.0.0.1:%d after %d ms, dir %s%n",
                kind.debianPackage, process.pid(), port, startupTime.toMillis(), runDir);
        return this;
    }

    /**
     * Stops the server process but keeps its port and state directory (accounts, rosters, vCards), so that
     * {@link #restart()} brings the same server back: for tests of clients that must survive a server restart.
     * Clients see their connection closed as the server shuts down.
     */
    public synchronized void stopServer() {
        stopProcess();
    }

    /** Starts the server stopped by {@link #stopServer()} again, on the same port with the same state. */
    public synchronized PrivateXmppServer restart() throws IOException, InterruptedException {
        if (process != null) {
            return this;
        }
        if (runDir == null) {
            return start();
        }
        Path root = repositoryRoot();
        process = switch (kind) {
            case PROSODY -> startProsody(root);
            case EJABBERD -> startEjabberd(root);
        };
        awaitReady();
        System.out.printf("[xmpp] private %s pid %d restarted on 127.0.0.1:%d%n", kind.debianPackage, process.pid(),
                port);
        return this;
    }

    private Process startProsody(Path root) throws IOException {
        ProcessBuilder pb = new ProcessBuilder(kind.executable, "--config",
                root.resolve("product/xmpp/prosody.cfg.lua").toString(), "-F");
        Map<String, String> env = pb.environment();
        env.put("SABOT_XMPP_RUN", runDir.toString());
        env.put("SABOT_C2S_PORT", Integer.toString(port));
        env.put("SABOT_ARCHIVE_STORE", "memory");
        env.put("SABOT_DOMAIN", DOMAIN);
        env.put("SABOT_DOMAIN2", SECOND_DOMAIN);
        if ("root".equals(System.getProperty("user.name"))) {
            env.put("SABOT_RUN_AS_ROOT", "1"); // Prosody refuses root, and then hangs, without run_as_root
        }
        pb.redirectErrorStream(true).redirectOutput(runDir.resolve("console.log").toFile());
        return pb.start();
    }

    private Process startEjabberd(Path root) throws IOException {
        int distPort = freeLoopbackPort();
        String suffix = runDir.getFileName().toString().replace('-', '_');
        Path template = root.resolve("product/xmpp");
        Files.writeString(runDir.resolve("ejabberd.yml"), Files.readString(template.resolve("ejabberd.yml.in"))
                .replace("@C2S_PORT@", Integer.toString(port)));
        Files.writeString(runDir.resolve("ejabberdctl.cfg"), Files.readString(template.resolve(
                "ejabberdctl.cfg.in")).replace("@NODE@", suffix + "@localhost")
                .replace("@DIST_PORT@", Integer.toString(distPort)).replace("@COOKIE@", "c" + UUID.randomUUID()
                        .toString().replace("-", "")));
        Files.copy(Paths.get("/etc/ejabberd/inetrc"), runDir.resolve("inetrc"),
                java.nio.file.StandardCopyOption.REPLACE_EXISTING); // (again on a restart)
        // The packaged control script only runs as root or 'ejabberd' and then su's to 'ejabberd', which cannot
        // write our directories. A private copy with INSTALLUSER emptied runs as the current user.
        Path ctl = runDir.resolve("ejabberdctl");
        Files.writeString(ctl, Files.readString(Paths.get(kind.executable)).replaceFirst("(?m)^INSTALLUSER=.*$",
                "INSTALLUSER="));
        ctl.toFile().setExecutable(true);
        Files.createDirectories(runDir.resolve("spool"));
        Files.createDirectories(runDir.resolve("logs"));
        ProcessBuilder pb = new ProcessBuilder(ctl.toString(), "--config-dir", runDir.toString(), "--config",
                runDir.resolve("ejabberd.yml").toString(), "--spool", runDir.resolve("spool").toString(), "--logs",
                runDir.resolve("logs").toString(), "foreground");
        pb.environment().put("HOME", runDir.toString());
        pb.environment().put("EJABBERD_PID_PATH", runDir.resolve("ejabberd.pid").toString());
        pb.redirectErrorStream(true).redirectOutput(runDir.resolve("console.log").toFile());
        return pb.start();
    }

    /** Readiness = the c2s listener answers a stream header with {@code </stream:features>}. */
    private void awaitReady() throws IOException, InterruptedException {
        long deadline = System.nanoTime() + READY_TIMEOUT.toNanos();
        byte[] header = ("<?xml version='1.0'?><stream:stream to='" + DOMAIN + "' version='1.0' "
                + "xmlns='jabber:client' xmlns:stream='http://etherx.jabber.org/streams'>")
                .getBytes(StandardCharsets.UTF_8);
        while (System.nanoTime() < deadline) {
            if (!process.isAlive()) {
                throw new IOException(kind.debianPackage + " exited with status " + process.exitValue()
                        + " before it was ready; see " + runDir.resolve("console.log") + ": " + tail("console.log"));
            }
            try (Socket s = new Socket()) {
                s.connect(new InetSocketAddress(InetAddress.getLoopbackAddress(), port), 500);
                s.setSoTimeout(2000);
                OutputStream out = s.getOutputStream();
                out.write(header);
                out.flush();
                InputStream in = s.getInputStream();
                StringBuilder reply = new StringBuilder();
                byte[] buf = new byte[4096];
                int n;
                while ((n = in.read(buf)) > 0) {
                    reply.append(new String(buf, 0, n, StandardCharsets.UTF_8));
                    if (reply.indexOf("</stream:features>") >= 0) {
                        return;
                    }
                }
            } catch (IOException notYet) {
                // listener not open yet: retry below
            }
            // Polling an external process's socket: there is no event to wait on.
            TimeUnit.MILLISECONDS.sleep(10);
        }
        stopProcess();
        throw new IOException(kind.debianPackage + " not ready within " + READY_TIMEOUT.toSeconds() + " s; see "
                + runDir);
    }

    private String tail(String file) {
        try {
            String s = Files.readString(runDir.resolve(file));
            return s.substring(Math.max(0, s.length() - 2000));
        } catch (IOException e) {
            return "(no " + file + ")";
        }
    }

    /** @return the server kind */
    public Kind kind() {
        return kind;
    }

    /** @return the c2s port on 127.0.0.1 */
    public int port() {
        return port;
    }

    /** @return the server's state directory (logs, data) */
    public Path runDir() {
        return runDir;
    }

    /** @return time from process start to the first stream features */
    public Duration startupTime() {
        return startupTime;
    }

    /** @return the operating-system process id of the server */
    public long pid() {
        return process.pid();
    }

    /**
     * A connection configuration for this server: loopback address (no DNS), plain TCP with TCP_NODELAY, no
     * compression. Callers may change it before {@code build()}.
     */
    public XMPPTCPConnectionConfiguration.Builder configuration(String localpart, String domain, String password) {
        try {
            return XMPPTCPConnectionConfiguration.builder()
                    .setXmppDomain(JidCreate.domainBareFrom(domain))
                    .setHostAddress(InetAddress.getLoopbackAddress())
                    .setPort(port)
                    .setUsernameAndPassword(localpart, password)
                    .setResource("test")
                    .setSecurityMode(SecurityMode.disabled)
                    .setSocketFactory(new NoDelaySocketFactory())
                    .setSendPresence(true)
                    .setConnectTimeout(10_000);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * Creates an account by in-band registration (XEP-0077), the way devices register themselves.
     *
     * @throws XMPPException.XMPPErrorException with condition {@code conflict} when the JID is taken
     */
    public EntityBareJid register(String localpart, String domain, String password) throws IOException,
            InterruptedException, SmackException, XMPPException {
        XMPPTCPConnection anonymous = new XMPPTCPConnection(configuration(localpart, domain, password).build());
        try {
            anonymous.connect();
            AccountManager accounts = AccountManager.getInstance(anonymous);
            accounts.sensitiveOperationOverInsecureConnection(true); // loopback only
            accounts.createAccount(Localpart.from(localpart), password);
            return JidCreate.entityBareFrom(localpart + "@" + domain);
        } finally {
            anonymous.disconnect();
        }
    }

    /** Registers {@code localpart@sabot.local} with the default password, connects and logs in. */
    public XMPPTCPConnection login(String localpart) throws IOException, InterruptedException, SmackException,
            XMPPException {
        return login(localpart, DOMAIN);
    }

    /** Registers {@code localpart@domain} with the default password, connects and logs in. */
    public XMPPTCPConnection login(String localpart, String domain) throws IOException, InterruptedException,
            SmackException, XMPPException {
        register(localpart, domain, DEFAULT_PASSWORD);
        return connect(configuration(localpart, domain, DEFAULT_PASSWORD).build());
    }

    /** Connects and logs in with a configuration; the connection is closed when the fixture stops. */
    public XMPPTCPConnection connect(XMPPTCPConnectionConfiguration configuration) throws IOException,
            InterruptedException, SmackException, XMPPException {
        XMPPTCPConnection connection = new XMPPTCPConnection(configuration);
        synchronized (connections) {
            connections.add(connection);
        }
        connection.connect().login();
        return connection;
    }

    /** @return the domain as a JID */
    public static DomainBareJid domainJid(String domain) {
        try {
            return JidCreate.domainBareFrom(domain);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Disconnects the fixture's connections and stops the server (SIGTERM, then SIGKILL after 3 s). */
    @Override
    public synchronized void close() {
        synchronized (connections) {
            for (XMPPTCPConnection c : connections) {
                if (c.isConnected()) {
                    c.instantShutdown();
                }
            }
            connections.clear();
        }
        stopProcess();
        if (shutdownHook != null) {
            try {
                Runtime.getRuntime().removeShutdownHook(shutdownHook);
            } catch (IllegalStateException shuttingDown) {
                // the hook is running or has run
            }
            shutdownHook = null;
        }
    }

    private void stopProcess() {
        Process p = process;
        if (p == null) {
            return;
        }
        // ejabberd's control script runs the Erlang VM as a child: stop the whole tree.
        List<ProcessHandle> tree = new ArrayList<>(p.descendants().toList());
        tree.forEach(ProcessHandle::destroy);
        p.destroy();
        try {
            if (!p.waitFor(STOP_GRACE.toMillis(), TimeUnit.MILLISECONDS)) {
                p.destroyForcibly();
                p.waitFor(STOP_GRACE.toMillis(), TimeUnit.MILLISECONDS);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            p.destroyForcibly();
        }
        tree.stream().filter(ProcessHandle::isAlive).forEach(ProcessHandle::destroyForcibly);
        System.out.printf("[xmpp] private %s pid %d stopped, alive=%s%n", kind.debianPackage, p.pid(), p.isAlive());
        process = null;
    }

    private static int freeLoopbackPort() throws IOException {
        try (ServerSocket s = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            return s.getLocalPort();
        }
    }

    /** The repository root: system property {@code sabot.root}, else the nearest parent holding product/xmpp. */
    public static Path repositoryRoot() {
        String configured = System.getProperty("sabot.root");
        if (configured != null && Files.isDirectory(Paths.get(configured, "product/xmpp"))) {
            return Paths.get(configured).toAbsolutePath();
        }
        for (Path p = Paths.get("").toAbsolutePath(); p != null; p = p.getParent()) {
            if (Files.isRegularFile(p.resolve("product/xmpp/prosody.cfg.lua"))) {
                return p;
            }
        }
        throw new IllegalStateException("cannot find the Sabot repository root (product/xmpp/prosody.cfg.lua); "
                + "set -Dsabot.root");
    }
}
