package sabot.onboard.portal.internal;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.URLDecoder;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import com.sun.net.httpserver.HttpExchange;
import com.sun.net.httpserver.HttpHandler;

import sabot.controlml.Role;
import sabot.onboard.config.SettingForm;
import sabot.onboard.config.SettingsChange;
import sabot.onboard.config.TaskForm;
import sabot.onboard.portal.internal.PortalSessions.Session;

/**
 * Every request of the page: one handler, one table of paths and methods. A request that does not fit is answered
 * with its HTTP error and a one-line reason: 400 (a malformed path or form), 401/303 (not logged in), 403 (a role
 * too low, a missing or wrong CSRF token, a foreign {@code Origin}), 404, 405 (with {@code Allow}), 413 (a body over
 * {@value #MAX_BODY} bytes), 415, 429 (log-ins throttled, with {@code Retry-After}).
 */
final class PortalRoutes implements HttpHandler {

    private static final Logger LOG = LoggerFactory.getLogger(PortalRoutes.class);

    /** The largest request body read: a configuration form of the largest task is under 4 KiB. */
    static final int MAX_BODY = 16 * 1024;
    /** The most fields one form may have. */
    static final int MAX_FIELDS = 128;
    static final String COOKIE = "sabot-portal";
    static final String FORM_TYPE = "application/x-www-form-urlencoded";

    /** Paths and the methods each accepts. */
    static final Map<String, Set<String>> ROUTES = Map.of("/", Set.of("GET"), "/login", Set.of("GET", "POST"),
            "/logout", Set.of("POST"), "/config", Set.of("GET", "POST"), "/api/status", Set.of("GET"), "/map.svg",
            Set.of("GET"), "/qr.png", Set.of("GET"), "/static/portal.css", Set.of("GET"), "/static/portal.js", Set.of(
                    "GET"));

    /** An answer other than 200, with the reason shown to the person. */
    static final class HttpError extends Exception {
        private static final long serialVersionUID = 1L;
        final int status;
        final Map<String, String> headers;

        HttpError(int status, String reason) {
            this(status, reason, Map.of());
        }

        HttpError(int status, String reason, Map<String, String> headers) {
            super(reason);
            this.status = status;
            this.headers = headers;
        }
    }

    private final PortalRobot robot;
    private final PortalSessions sessions;
    private final LoginThrottle throttle;
    private final boolean secure;
    private final long pollMs;
    private final Map<String, byte[]> assets;

    PortalRoutes(PortalRobot robot, PortalSessions sessions, LoginThrottle throttle, boolean secure, Duration poll,
            Map<String, byte[]> assets) {
        this.robot = robot;
        this.sessions = sessions;
        this.throttle = throttle;
        this.secure = secure;
        this.pollMs = poll.toMillis();
        this.assets = assets;
    }

    @Override
    public void handle(HttpExchange exchange) throws IOException {
        try {
            var h = exchange.getResponseHeaders();
            h.set("X-Content-Type-Options", "nosniff");
            h.set("Referrer-Policy", "same-origin");
            h.set("X-Frame-Options", "DENY");
            if (secure) { // browsers that once saw the page over HTTPS never try it in clear
                h.set("Strict-Transport-Security", "max-age=31536000");
            }
            h.set("Content-Security-Policy", "default-src 'none'; img-src 'self'; style-src 'self'; script-src 'self'; "
                    + "connect-src 'self'; form-action 'self'; frame-ancestors 'none'; base-uri 'none'");
            route(exchange);
        } catch (HttpError e) {
            e.headers.forEach(exchange.getResponseHeaders()::set);
            if (exchange.getRequestURI().getRawPath().startsWith("/api/")) {
                send(exchange, e.status, "application/json", Json.write(Map.of("error", e.getMessage())).getBytes(
                        StandardCharsets.UTF_8));
            } else {
                send(exchange, e.status, "text/html; charset=utf-8", PortalPages.error(e.status, reason(e.status), e
                        .getMessage()).getBytes(StandardCharsets.UTF_8));
            }
        } catch (IOException e) {
            LOG.debug("portal: {} {}: {}", exchange.getRequestMethod(), exchange.getRequestURI(), e.toString());
        } catch (RuntimeException e) {
            LOG.warn("portal: {} {} failed", exchange.getRequestMethod(), exchange.getRequestURI().getRawPath(), e);
            try {
                send(exchange, 500, "text/html; charset=utf-8", PortalPages.error(500, reason(500), "the robot could "
                        + "not answer: " + e).getBytes(StandardCharsets.UTF_8));
            } catch (IOException | RuntimeException ignored) {
                // headers already sent: the connection is closed below
            }
        } finally {
            exchange.close();
        }
    }

    private void route(HttpExchange x) throws IOException, HttpError {
        String path = x.getRequestURI().getRawPath();
        String method = x.getRequestMethod();
        if (path == null || !path.matches("/[A-Za-z0-9._/-]*") || path.contains("..") || path.contains("//")) {
            throw new HttpError(400, "the path '" + (path == null ? "" : path) + "' is not one of this page's (only "
                    + "letters, digits, '.', '_', '-' and single '/', no '..')");
        }
        Set<String> methods = ROUTES.get(path);
        if (methods == null) {
            throw new HttpError(404, "this page has nothing at " + path);
        }
        if (!methods.contains(method)) {
            throw new HttpError(405, method + " is not allowed on " + path + " (allowed: " + String.join(", ",
                    methods.stream().sorted().toList()) + ")", Map.of("Allow", String.join(", ", methods.stream()
                            .sorted().toList())));
        }
        if (path.startsWith("/static/")) {
            byte[] asset = assets.get(path);
            if (asset == null) {
                throw new HttpError(404, "this page has nothing at " + path);
            }
            x.getResponseHeaders().set("Cache-Control", "max-age=3600");
            send(x, 200, path.endsWith(".css") ? "text/css; charset=utf-8" : "text/javascript; charset=utf-8", asset);
            return;
        }
        x.getResponseHeaders().set("Cache-Control", "no-store");
        if (path.equals("/login")) {
            if (method.equals("GET")) {
                html(x, 200, PortalPages.login(robotName(), null, ""));
            } else {
                login(x);
            }
            return;
        }
        Optional<Session> found = sessions.find(cookie(x));
        if (found.isEmpty()) {
            if (method.equals("GET") && !path.startsWith("/api/")) {
                x.getResponseHeaders().set("Location", "/login");
                send(x, 303, "text/plain; charset=utf-8", "log in first\n".getBytes(StandardCharsets.UTF_8));
                return;
            }
            throw new HttpError(401, "not logged in, or the session has ended: log in again");
        }
        Session session = found.get();
        Role role = robot.roleOf(session.account()); // again at each request: a revoked role ends here
        if (!role.includes(Role.OBSERVER)) {
            sessions.close(session.id());
            throw new HttpError(403, session.account() + " has no role on this robot any more");
        }
        switch (path) {
            case "/" -> html(x, 200, PortalPages.status(robotName(), session, role, robot.map().map(MapSvg::of)
                    .orElse(null), pollMs));
            case "/api/status" -> {
                Map<String, Object> status = new LinkedHashMap<>(robot.robotState());
                status.put("account", session.account());
                status.put("role", role.label());
                send(x, 200, "application/json", Json.write(status).getBytes(StandardCharsets.UTF_8));
            }
            case "/map.svg" -> send(x, 200, "image/svg+xml", robot.map().map(MapSvg::of).orElseThrow(
                    () -> new HttpError(404, "the robot has no map (the motion task does not run)")).getBytes(
                            StandardCharsets.UTF_8));
            case "/qr.png" -> send(x, 200, "image/png", robot.inventoryQr().orElseThrow(() -> new HttpError(404,
                    "the robot's QR inventory is not available (not published yet, or the session is offline)")));
            case "/logout" -> {
                Map<String, String> form = form(x);
                checkCsrf(session, form);
                sessions.close(session.id());
                LOG.info("portal: {} logged out", session.account());
                x.getResponseHeaders().add("Set-Cookie", cookieHeader("", 0));
                x.getResponseHeaders().set("Location", "/login");
                send(x, 303, "text/plain; charset=utf-8", "logged out\n".getBytes(StandardCharsets.UTF_8));
            }
            case "/config" -> {
                if (!role.includes(Role.MAINTAINER)) {
                    throw new HttpError(403, "the configuration is for maintainers; " + session.account() + " is "
                            + role.withArticle() + " of this robot");
                }
                if (method.equals("GET")) {
                    html(x, 200, PortalPages.config(robotName(), session, role, robot.settings().file().toString(),
                            robot.settings().tasks(), null, null, null));
                } else {
                    Map<String, String> form = form(x);
                    checkCsrf(session, form);
                    change(x, session, role, form);
                }
            }
            default -> throw new HttpError(404, "this page has nothing at " + path);
        }
    }

    private void login(HttpExchange x) throws IOException, HttpError {
        checkOrigin(x);
        Map<String, String> form = form(x);
        String account = form.getOrDefault("account", "").strip();
        String password = form.getOrDefault("password", "");
        if (account.isEmpty() || password.isEmpty() || account.length() > 256 || password.length() > 1024) {
            throw new HttpError(400, "the log-in form needs an account (name@domain) and a password");
        }
        String client = x.getRemoteAddress().getAddress().getHostAddress();
        Duration wait = throttle.wait(client, account);
        if (!wait.isZero() && !wait.isNegative()) {
            long seconds = Math.max(1, (wait.toMillis() + 999) / 1000);
            LOG.warn("portal: log-in as {} from {} refused: too many failed log-ins", account, client);
            throw new HttpError(429, "too many failed log-ins from this address or for this account: try again in "
                    + seconds + " s", Map.of("Retry-After", Long.toString(seconds)));
        }
        boolean accepted;
        try {
            accepted = robot.checkPassword(account, password);
        } catch (IOException e) {
            throw new HttpError(503, "the robot's XMPP server could not check the password: " + e.getMessage());
        }
        if (!accepted) {
            throttle.failed(client, account);
            LOG.warn("portal: failed log-in as {} from {}", account, client);
            html(x, 401, PortalPages.login(robotName(), "wrong account or password", account));
            return;
        }
        Role role = robot.roleOf(account);
        if (!role.includes(Role.OBSERVER)) {
            LOG.warn("portal: {} logged in from {} but has no role on this robot", account, client);
            html(x, 403, PortalPages.login(robotName(), account + " has no role on this robot (the lab grants roles "
                    + "through its server's groups)", account));
            return;
        }
        Session session = sessions.open(account);
        LOG.info("portal: {} logged in from {} as {}", account, client, role.withArticle());
        x.getResponseHeaders().add("Set-Cookie", cookieHeader(session.id(), -1));
        x.getResponseHeaders().set("Location", "/");
        send(x, 303, "text/plain; charset=utf-8", "logged in\n".getBytes(StandardCharsets.UTF_8));
    }

    private void change(HttpExchange x, Session session, Role role, Map<String, String> form) throws IOException,
            HttpError {
        String task = form.get("task");
        if (task == null || task.isBlank()) {
            throw new HttpError(400, "the form names no task");
        }
        Optional<TaskForm> current = robot.settings().tasks().stream().filter(t -> t.name().equals(task)).findFirst();
        Map<String, String> changed = new LinkedHashMap<>();
        for (Map.Entry<String, String> field : form.entrySet()) {
            if (!field.getKey().startsWith("s.")) {
                if (!field.getKey().equals("csrf") && !field.getKey().equals("task")) {
                    throw new HttpError(400, "the form has a field '" + field.getKey() + "' that is no setting");
                }
                continue;
            }
            String id = field.getKey().substring(2);
            String value = field.getValue().strip();
            String before = current.flatMap(t -> t.settings().stream().filter(s -> s.id().equals(id)).findFirst())
                    .map(SettingForm::value).orElse(null);
            if (!value.equals(before == null ? "" : before) || current.isEmpty()) {
                changed.put(id, value);
            }
        }
        SettingsChange outcome = robot.settings().change(task, changed);
        if (outcome.applied()) {
            LOG.info("portal: {} changed {} settings {}: {}", session.account(), task, changed.keySet(), outcome
                    .message());
        } else {
            LOG.warn("portal: {} asked to change {} settings {}: refused: {}", session.account(), task, changed
                    .keySet(), outcome.message());
        }
        html(x, outcome.applied() ? 200 : 400, PortalPages.config(robotName(), session, role, robot.settings().file()
                .toString(), robot.settings().tasks(), outcome.applied() ? outcome.message() : null, outcome.applied()
                        ? null : outcome.message(), task));
    }

    private static void checkCsrf(Session session, Map<String, String> form) throws HttpError {
        if (!session.csrfMatches(form.get("csrf"))) {
            throw new HttpError(403, "the form's CSRF token is missing or wrong: nothing changed (reload the page "
                    + "and try again)");
        }
    }

    /** A browser's log-in from another site's page is refused (the session forms carry a CSRF token instead). */
    private static void checkOrigin(HttpExchange x) throws HttpError {
        String origin = x.getRequestHeaders().getFirst("Origin");
        String host = x.getRequestHeaders().getFirst("Host");
        if (origin != null && !origin.equals("null") && host != null && !origin.endsWith("://" + host)) {
            throw new HttpError(403, "a log-in from another site (" + origin + ") is refused");
        }
    }

    /** @return the request's form: application/x-www-form-urlencoded, at most {@value #MAX_BODY} bytes */
    static Map<String, String> form(HttpExchange x) throws IOException, HttpError {
        String type = x.getRequestHeaders().getFirst("Content-Type");
        String length = x.getRequestHeaders().getFirst("Content-Length");
        if (length != null) {
            long n;
            try {
                n = Long.parseLong(length.strip());
            } catch (NumberFormatException e) {
                throw new HttpError(400, "Content-Length '" + length + "' is not a number");
            }
            if (n > MAX_BODY) {
                throw new HttpError(413, "the request's body of " + n + " bytes is over this page's limit of "
                        + MAX_BODY + " bytes", Map.of("Connection", "close"));
            }
        }
        byte[] body;
        try (InputStream in = x.getRequestBody()) {
            body = in.readNBytes(MAX_BODY + 1);
        }
        if (body.length > MAX_BODY) {
            throw new HttpError(413, "the request's body is over this page's limit of " + MAX_BODY + " bytes", Map.of(
                    "Connection", "close"));
        }
        if (type == null || !type.toLowerCase(java.util.Locale.ROOT).startsWith(FORM_TYPE)) {
            throw new HttpError(415, "a form (" + FORM_TYPE + ") is expected, not " + (type == null ? "no type"
                    : "'" + type + "'"));
        }
        return parseForm(new String(body, StandardCharsets.UTF_8));
    }

    /** @throws HttpError 400 for a malformed form: bad percent-encoding, a field twice, too many fields */
    static Map<String, String> parseForm(String body) throws HttpError {
        Map<String, String> fields = new LinkedHashMap<>();
        if (body.isEmpty()) {
            return fields;
        }
        String[] pairs = body.split("&", -1);
        if (pairs.length > MAX_FIELDS) {
            throw new HttpError(400, "the form has more than " + MAX_FIELDS + " fields");
        }
        for (String pair : pairs) {
            int eq = pair.indexOf('=');
            if (eq <= 0) {
                throw new HttpError(400, "the form is malformed: '" + abbreviate(pair) + "' is not name=value");
            }
            String name;
            String value;
            try {
                name = URLDecoder.decode(pair.substring(0, eq), StandardCharsets.UTF_8);
                value = URLDecoder.decode(pair.substring(eq + 1), StandardCharsets.UTF_8);
            } catch (IllegalArgumentException e) {
                throw new HttpError(400, "the form is malformed: " + e.getMessage());
            }
            if (fields.put(name, value) != null) {
                throw new HttpError(400, "the form has the field '" + abbreviate(name) + "' twice");
            }
        }
        return fields;
    }

    private static String abbreviate(String s) {
        return s.length() > 40 ? s.substring(0, 40) + "…" : s;
    }

    private String cookieHeader(String value, int maxAge) {
        return COOKIE + "=" + value + "; Path=/; HttpOnly; SameSite=Strict" + (secure ? "; Secure" : "")
                + (maxAge >= 0 ? "; Max-Age=" + maxAge : "");
    }

    private static String cookie(HttpExchange x) {
        List<String> headers = x.getRequestHeaders().get("Cookie");
        if (headers == null) {
            return null;
        }
        for (String header : headers) {
            for (String part : header.split(";")) {
                String p = part.strip();
                if (p.startsWith(COOKIE + "=")) {
                    return p.substring(COOKIE.length() + 1);
                }
            }
        }
        return null;
    }

    private String robotName() {
        return robot.settings().robotName();
    }

    private static void html(HttpExchange x, int status, String page) throws IOException {
        send(x, status, "text/html; charset=utf-8", page.getBytes(StandardCharsets.UTF_8));
    }

    private static void send(HttpExchange x, int status, String type, byte[] body) throws IOException {
        x.getResponseHeaders().set("Content-Type", type);
        x.sendResponseHeaders(status, body.length == 0 ? -1 : body.length);
        if (body.length > 0) {
            try (OutputStream out = x.getResponseBody()) {
                out.write(body);
            }
        }
    }

    private static String reason(int status) {
        return switch (status) {
            case 400 -> "Bad Request";
            case 401 -> "Unauthorized";
            case 403 -> "Forbidden";
            case 404 -> "Not Found";
            case 405 -> "Method Not Allowed";
            case 413 -> "Content Too Large";
            case 415 -> "Unsupported Media Type";
            case 429 -> "Too Many Requests";
            case 503 -> "Service Unavailable";
            default -> "Internal Server Error";
        };
    }
}
