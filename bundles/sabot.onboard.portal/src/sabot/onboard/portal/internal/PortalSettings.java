package sabot.onboard.portal.internal;

import java.net.InetAddress;
import java.net.UnknownHostException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.time.Duration;
import java.util.List;
import java.util.Map;

import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;

import sabot.onboard.task.SettingsParser;
import sabot.onboard.task.OnboardTask;
import sabot.onboard.task.TaskProperties;
import sabot.onboard.task.TaskSettingsCheck.Problem;

/**
 * The settings of the {@code portal} task (declared by {@link Config}).
 *
 * @param bind           the address the server listens on
 * @param port           its TCP port
 * @param address        the host part of the page's address as people reach it (the vCard's URL)
 * @param tls            the server certificate and key when the page is served over HTTPS, else null (plain HTTP)
 * @param sessionTimeout a log-in's life without a request
 * @param throttle       how many failed log-ins a client or an account may have in which window
 * @param poll           how often the status page asks for the robot's state
 * @param requestTimeout how long a request's body may take to arrive once its headers have
 */
public record PortalSettings(InetAddress bind, int port, String address, PemIdentity.Files tls, Duration sessionTimeout,
        LoginThrottle.Limits throttle, Duration poll, Duration requestTimeout) {

    /** The task's name. */
    public static final String TASK = "portal";

    static final int DEFAULT_PORT = 8080;
    static final String DEFAULT_BIND = "0.0.0.0";
    static final int DEFAULT_SESSION_TIMEOUT_S = 900;
    static final int DEFAULT_LOGIN_FAILURES = 5;
    static final int DEFAULT_LOGIN_WINDOW_S = 60;
    static final int DEFAULT_POLL_MS = 250;
    static final int DEFAULT_REQUEST_TIMEOUT_S = 10;

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = OnboardTask.PID_PREFIX + TASK, name = "Web page",
            description = "The robot's own web page: status for every role, settings for maintainers; log-in with the "
                    + "robot's XMPP accounts.")
    public @interface Config {
        @AttributeDefinition(name = "Bind address", description = "The address the page listens on: 0.0.0.0 for "
                + "every interface, 127.0.0.1 for this computer only.")
        String bind() default DEFAULT_BIND;

        @AttributeDefinition(name = "Port", description = "The page's TCP port.", min = "1", max = "65535")
        int port() default DEFAULT_PORT;

        @AttributeDefinition(name = "Address", required = false, description = "The host name or address people "
                + "reach the page at (the robot's vCard URL); empty: the bind address, or this computer's name when "
                + "it listens on every interface.")
        String address() default "";

        @AttributeDefinition(name = "HTTPS", description = "true: served over TLS with the certificate and key below "
                + "(e.g. the lab CA's, certs/DOMAIN.crt and .key of the private XMPP server); the session cookie is "
                + "then Secure. false: plain HTTP, for a robot on a closed network only.")
        boolean tls() default false;

        @AttributeDefinition(name = "Certificate file", required = false, description = "PEM file of the server's "
                + "certificate (and its chain) when HTTPS is on.")
        String certificateFile() default "";

        @AttributeDefinition(name = "Key file", required = false, description = "PEM file of the certificate's "
                + "private key (PKCS #8, unencrypted) when HTTPS is on; readable by the robot's user only.")
        String keyFile() default "";

        @AttributeDefinition(name = "Session timeout", description = "Seconds a log-in lasts without a request.",
                min = "60", max = "86400")
        int sessionTimeout() default DEFAULT_SESSION_TIMEOUT_S;

        @AttributeDefinition(name = "Failed log-ins", description = "Failed log-ins a client address, or an "
                + "account, may have within the window below; more are refused without asking the server.", min = "1",
                max = "1000")
        int loginFailures() default DEFAULT_LOGIN_FAILURES;

        @AttributeDefinition(name = "Log-in window", description = "Seconds over which failed log-ins are counted.",
                min = "1", max = "86400")
        int loginWindow() default DEFAULT_LOGIN_WINDOW_S;

        @AttributeDefinition(name = "Status poll interval", description = "Milliseconds between two requests of the "
                + "status page for the robot's state (while somebody looks at it).", min = "50", max = "10000")
        int pollInterval() default DEFAULT_POLL_MS;

        @AttributeDefinition(name = "Request timeout", description = "Seconds a request's body may take to arrive "
                + "once its headers have; a slower one is answered 408. Read without holding a thread, so slow "
                + "clients do not keep others waiting.", min = "1", max = "300")
        int requestTimeout() default DEFAULT_REQUEST_TIMEOUT_S;
    }

    /**
     * @param properties the task's configuration
     * @return the settings
     * @throws sabot.onboard.task.InvalidSettings listing every problem
     */
    public static PortalSettings of(Map<String, ?> properties) {
        return PARSER.of(TASK, properties);
    }

    /** @return the problems of a configuration; empty when {@link #of} would succeed */
    public static List<Problem> problems(Map<String, ?> properties) {
        return PARSER.problems(properties);
    }

    /** The one parse behind {@link #of} and {@link #problems}. */
    private static final SettingsParser<PortalSettings> PARSER = PortalSettings::parse;

    /** @return the page's address, e.g. {@code https://robot-1.lab:8443/} */
    public String url() {
        return (tls != null ? "https" : "http") + "://" + (address.indexOf(':') >= 0 ? "[" + address + "]" : address)
                + ":" + port + "/";
    }

    private static PortalSettings parse(Map<String, ?> properties, List<Problem> problems) {
        TaskProperties p = new TaskProperties(properties);
        InetAddress bind = null;
        String bindText = p.string("bind", DEFAULT_BIND).strip();
        try {
            if (!bindText.matches("[0-9.]+|[0-9a-fA-F:]+|localhost")) {
                problems.add(new Problem("bind", "'" + bindText + "' is not an IP address"));
            } else {
                bind = InetAddress.getByName(bindText); // a literal: no name lookup
            }
        } catch (UnknownHostException e) {
            problems.add(new Problem("bind", "'" + bindText + "' is not an IP address"));
        }
        long port = integer(p, "port", DEFAULT_PORT, 1, 65535, problems);
        long timeout = integer(p, "sessionTimeout", DEFAULT_SESSION_TIMEOUT_S, 60, 86400, problems);
        long failures = integer(p, "loginFailures", DEFAULT_LOGIN_FAILURES, 1, 1000, problems);
        long window = integer(p, "loginWindow", DEFAULT_LOGIN_WINDOW_S, 1, 86400, problems);
        long poll = integer(p, "pollInterval", DEFAULT_POLL_MS, 50, 10000, problems);
        long request = integer(p, "requestTimeout", DEFAULT_REQUEST_TIMEOUT_S, 1, 300, problems);
        boolean tls = false;
        try {
            tls = p.bool("tls", false);
        } catch (IllegalArgumentException e) {
            problems.add(new Problem("tls", e.getMessage()));
        }
        PemIdentity.Files files = null;
        if (tls) {
            Path certificate = file(p, "certificateFile", problems);
            Path key = file(p, "keyFile", problems);
            if (certificate != null && key != null) {
                files = new PemIdentity.Files(certificate, key);
                try {
                    PemIdentity.load(files);
                } catch (java.io.IOException | java.security.GeneralSecurityException e) {
                    problems.add(new Problem("certificateFile", "cannot use " + certificate + " with " + key + ": "
                            + e.getMessage()));
                }
            }
        }
        String address = p.string("address", "").strip();
        if (address.isEmpty() && bind != null) {
            address = bind.isAnyLocalAddress() ? hostName() : bind.getHostAddress();
        }
        if (!address.matches("[A-Za-z0-9.:-]*")) {
            problems.add(new Problem("address", "'" + address + "' is not a host name or an IP address"));
        }
        if (!problems.isEmpty()) {
            return null;
        }
        return new PortalSettings(bind, (int) port, address, files, Duration.ofSeconds(timeout),
                new LoginThrottle.Limits((int) failures, Duration.ofSeconds(window)), Duration.ofMillis(poll),
                Duration.ofSeconds(request));
    }

    private static String hostName() {
        try {
            return InetAddress.getLocalHost().getHostName();
        } catch (UnknownHostException e) {
            return "localhost";
        }
    }

    private static Path file(TaskProperties p, String key, List<Problem> problems) {
        String name = p.string(key, "").strip();
        if (name.isEmpty()) {
            problems.add(new Problem(key, "HTTPS is on (tls = true): this file must be given"));
            return null;
        }
        Path file = Paths.get(name).toAbsolutePath().normalize();
        if (!Files.isRegularFile(file)) {
            problems.add(new Problem(key, "file " + file + " does not exist"));
            return null;
        }
        if (!Files.isReadable(file)) {
            problems.add(new Problem(key, "file " + file + " is not readable by this process (user "
                    + System.getProperty("user.name") + ")"));
            return null;
        }
        return file;
    }

    private static long integer(TaskProperties p, String key, long fallback, long min, long max,
            List<Problem> problems) {
        try {
            long v = p.integer(key, fallback);
            if (v < min || v > max) {
                problems.add(new Problem(key, "'" + v + "' is outside " + min + ".." + max));
            }
            return v;
        } catch (IllegalArgumentException e) {
            problems.add(new Problem(key, e.getMessage()));
            return fallback;
        }
    }
}
