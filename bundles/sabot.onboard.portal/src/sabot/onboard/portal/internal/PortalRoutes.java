package sabot.onboard.portal.internal;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.net.URLDecoder;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.atomic.AtomicBoolean;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import jakarta.servlet.AsyncContext;
import jakarta.servlet.AsyncEvent;
import jakarta.servlet.AsyncListener;
import jakarta.servlet.ReadListener;
import jakarta.servlet.ServletInputStream;
import jakarta.servlet.http.HttpServlet;
import jakarta.servlet.http.HttpServletRequest;
import jakarta.servlet.http.HttpServletResponse;
import sabot.controlml.Role;
import sabot.onboard.config.SettingForm;
import sabot.onboard.config.SettingsChange;
import sabot.onboard.config.TaskForm;
import sabot.onboard.portal.internal.PortalSessions.Session;

/**
 * Every request of the page: one servlet on the Servlet Whiteboard, one table of paths and methods. A request that does
 * not fit is answered with its HTTP error and a one-line reason: 400 (a malformed path or form), 401/303 (not logged
 * in), 403 (a role too low, a missing or wrong CSRF token, a foreign {@code Origin}), 404, 405 (with {@code Allow}), 408
 * (a body not arrived within the request timeout), 413 (a body over {@value #MAX_BODY} bytes), 415, 429
 * (log-ins throttled, with {@code Retry-After}). A body is read without blocking ({@link ReadListener}): a client
 * sending slowly holds no thread, only its connection.
 */
final class PortalRoutes extends HttpServlet {

    private static final long serialVersionUID = 1L;

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

    private final transient PortalRobot robot;
    private final transient PortalSessions sessions;
    private final transient LoginThrottle throttle;
    private final boolean secure;
    private final long pollMs;
    private final long bodyTimeoutMs;
    private final transient Map<String, byte[]> assets;

    PortalRoutes(PortalRobot robot, PortalSessions sessions, LoginThrottle throttle, boolean secure, Duration poll,
            Duration bodyTimeout, Map<String, byte[]> assets) {
        this.robot = robot;
        this.sessions = sessions;
        this.throttle = throttle;
        this.secure = secure;
        this.pollMs = poll.toMillis();
        this.bodyTimeoutMs = bodyTimeout.toMillis();
        this.assets = assets;
    }

    @Override
    protected void service(HttpServletRequest request, HttpServletResponse response) {
        Exchange x = new Exchange(request, response);
        response.setHeader("X-Content-Type-Options", "nosniff");
        response.setHeader("Referrer-Policy", "same-origin");
        response.setHeader("X-Frame-Options", "DENY");
        if (secure) { // browsers that once saw the page over HTTPS never try it in clear
            response.setHeader("Strict-Transport-Security", "max-age=31536000");
        }
        response.setHeader("Content-Security-Policy", "default-src 'none'; img-src 'self'; style-src 'self'; "
                + "script-src 'self'; connect-src 'self'; form-action 'self'; frame-ancestors 'none'; base-uri 'none'");
        try {
            String path = check(x);
            if (x.method().equals("POST")) {
                readBody(x, path);
            } else {
                answer(x, () -> route(x, path, null));
            }
        } catch (HttpError e) {
            answer(x, () -> {
                throw e;
            });
        }
    }

    /** One step of answering a request, which may end in an {@link HttpError}. */
    private interface Step {
        void run() throws IOException, HttpError;
    }

    /** Runs {@code step}; its {@link HttpError} (or failure) becomes the error's page or JSON. */
    private void answer(Exchange x, Step step) {
        try {
            step.run();
        } catch (HttpError e) {
            e.headers.forEach(x.response()::setHeader);
            try {
                if (x.path().startsWith("/api/")) {
                    send(x, e.status, "application/json", Json.write(Map.of("error", e.getMessage())).getBytes(
                            StandardCharsets.UTF_8));
                } else {
                    send(x, e.status, "text/html; charset=utf-8", PortalPages.error(e.status, reason(e.status), e
                            .getMessage()).getBytes(StandardCharsets.UTF_8));
                }
            } catch (IOException | IllegalStateException ignored) {
                LOG.debug("portal: {} {}: the error {} could not be sent: {}", x.method(), x.path(), e.status,
                        ignored.toString());
            }
        } catch (IOException e) {
            LOG.debug("portal: {} {}: {}", x.method(), x.path(), e.toString());
        } catch (RuntimeException e) {
            LOG.warn("portal: {} {} failed", x.method(), x.path(), e);
            try {
                send(x, 500, "text/html; charset=utf-8", PortalPages.error(500, reason(500), "the robot could "
                        + "not answer: " + e).getBytes(StandardCharsets.UTF_8));
            } catch (IOException | RuntimeException ignored) {
                // headers already sent: the container closes the connection
            }
        }
    }

    /**
     * Reads a POST's form without holding a thread while it arrives, then answers it: 413 by {@code Content-Length}
     * before reading or while reading, 408 when the body has not arrived within the request timeout.
     */
    private void readBody(Exchange x, String path) throws HttpError {
        String length = x.request().getHeader("Content-Length");
        if (length != null) {
            long n;
            try {
                n = Long.parseLong(length.strip());
            } catch (NumberFormatException e) {
                throw new HttpError(400, "Content-Length '" + length + "' is not a number");
            }
            if (n > MAX_BODY) {
                throw tooLarge(" of " + n + " bytes");
            }
        }
        AsyncContext async = x.request().startAsync();
        async.setTimeout(bodyTimeoutMs);
        ServletInputStream in;
        try {
            in = x.request().getInputStream();
        } catch (IOException e) {
            async.complete();
            LOG.debug("portal: POST {}: {}", path, e.toString());
            return;
        }
        ByteArrayOutputStream body = new ByteArrayOutputStream();
        AtomicBoolean done = new AtomicBoolean();
        async.addListener(new AsyncListener() {
            @Override
            public void onTimeout(AsyncEvent event) {
                if (done.compareAndSet(false, true)) {
                    LOG.debug("portal: POST {} from {}: the body did not arrive in time", path, x.request()
                            .getRemoteAddr());
                    x.response().setHeader("Connection", "close");
                    answer(x, () -> {
                        throw new HttpError(408, "the request's body did not arrive within " + bodyTimeoutMs
                                + " ms");
                    });
                    async.complete();
                }
            }

            @Override
            public void onError(AsyncEvent event) {
                done.set(true);
            }

            @Override
            public void onStartAsync(AsyncEvent event) {
                // nothing: one asynchronous phase per request
            }

            @Override
            public void onComplete(AsyncEvent event) {
                // nothing: the answer is written before completing
            }
        });
        in.setReadListener(new ReadListener() {
            private final byte[] buffer = new byte[4096];

            @Override
            public void onDataAvailable() throws IOException {
                while (in.isReady() && !done.get()) {
                    int n = in.read(buffer);
                    if (n < 0) {
                        return; // onAllDataRead follows
                    }
                    body.write(buffer, 0, n);
                    if (body.size() > MAX_BODY && done.compareAndSet(false, true)) {
                        answer(x, () -> {
                            throw tooLarge("");
                        });
                        async.complete();
                        return;
                    }
                }
            }

            @Override
            public void onAllDataRead() {
                if (done.compareAndSet(false, true)) {
                    answer(x, () -> route(x, path, body.toByteArray()));
                    async.complete();
                }
            }

            @Override
            public void onError(Throwable t) {
                if (done.compareAndSet(false, true)) {
                    LOG.debug("portal: POST {} from {}: {}", path, x.request().getRemoteAddr(), t.toString());
                    async.complete();
                }
            }
        });
    }

    private static HttpError tooLarge(String size) {
        return new HttpError(413, "the request's body" + size + " is over this page's limit of " + MAX_BODY
                + " bytes", Map.of("Connection", "close"));
    }

    /** @return the request's path, checked: one of the page's, with a method it accepts */
    private static String check(Exchange x) throws HttpError {
        String path = x.path();
        String method = x.method();
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
        return path;
    }

    /** Answers a checked request; {@code body} is a POST's body, {@code null} for the other methods. */
    private void route(Exchange x, String path, byte[] body) throws IOException, HttpError {
        String method = x.method();
        if (path.startsWith("/static/")) {
            byte[] asset = assets.get(path);
            if (asset == null) {
                throw new HttpError(404, "this page has nothing at " + path);
            }
            x.response().setHeader("Cache-Control", "max-age=3600");
            send(x, 200, path.endsWith(".css") ? "text/css; charset=utf-8" : "text/javascript; charset=utf-8", asset);
            return;
        }
        x.response().setHeader("Cache-Control", "no-store");
        if (path.equals("/login")) {
            if (method.equals("GET")) {
                html(x, 200, PortalPages.login(robotName(), null, ""));
            } else {
                login(x, body);
            }
            return;
        }
        Optional<Session> found = sessions.find(cookie(x));
        if (found.isEmpty()) {
            if (method.equals("GET") && !path.startsWith("/api/")) {
                x.response().setHeader("Location", "/login");
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
                Map<String, String> form = form(x, body);
                checkCsrf(session, form);
                sessions.close(session.id());
                LOG.info("portal: {} logged out", session.account());
                x.response().addHeader("Set-Cookie", cookieHeader("", 0));
                x.response().setHeader("Location", "/login");
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
                    Map<String, String> form = form(x, body);
                    checkCsrf(session, form);
                    change(x, session, role, form);
                }
            }
            default -> throw new HttpError(404, "this page has nothing at " + path);
        }
    }

    private void login(Exchange x, byte[] body) throws IOException, HttpError {
        checkOrigin(x);
        Map<String, String> form = form(x, body);
        String account = form.getOrDefault("account", "").strip();
        String password = form.getOrDefault("password", "");
        if (account.isEmpty() || password.isEmpty() || account.length() > 256 || password.length() > 1024) {
            throw new HttpError(400, "the log-in form needs an account (name@domain) and a password");
        }
        String client = x.request().getRemoteAddr();
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
        x.response().addHeader("Set-Cookie", cookieHeader(session.id(), -1));
        x.response().setHeader("Location", "/");
        send(x, 303, "text/plain; charset=utf-8", "logged in\n".getBytes(StandardCharsets.UTF_8));
    }

    private void change(Exchange x, Session session, Role role, Map<String, String> form) throws IOException,
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
    private static void checkOrigin(Exchange x) throws HttpError {
        String origin = x.request().getHeader("Origin");
        String host = x.request().getHeader("Host");
        if (origin != null && !origin.equals("null") && host != null && !origin.endsWith("://" + host)) {
            throw new HttpError(403, "a log-in from another site (" + origin + ") is refused");
        }
    }

    /** @return the request's form: application/x-www-form-urlencoded, its body read by {@link #readBody} */
    static Map<String, String> form(Exchange x, byte[] body) throws HttpError {
        String type = x.request().getContentType();
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

    private static String cookie(Exchange x) {
        for (String header : java.util.Collections.list(x.request().getHeaders("Cookie"))) {
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

    private static void html(Exchange x, int status, String page) throws IOException {
        send(x, status, "text/html; charset=utf-8", page.getBytes(StandardCharsets.UTF_8));
    }

    private static void send(Exchange x, int status, String type, byte[] body) throws IOException {
        HttpServletResponse r = x.response();
        r.setStatus(status);
        r.setContentType(type);
        r.setContentLength(body.length);
        if (body.length > 0) {
            r.getOutputStream().write(body);
        }
        r.flushBuffer();
    }

    private static String reason(int status) {
        return switch (status) {
            case 400 -> "Bad Request";
            case 401 -> "Unauthorized";
            case 403 -> "Forbidden";
            case 404 -> "Not Found";
            case 405 -> "Method Not Allowed";
            case 408 -> "Request Timeout";
            case 413 -> "Content Too Large";
            case 415 -> "Unsupported Media Type";
            case 429 -> "Too Many Requests";
            case 503 -> "Service Unavailable";
            default -> "Internal Server Error";
        };
    }

    /** A request and its response; the path is the raw (not decoded) request URI's path. */
    record Exchange(HttpServletRequest request, HttpServletResponse response) {

        String path() {
            return request.getRequestURI();
        }

        String method() {
            return request.getMethod();
        }
    }
}
