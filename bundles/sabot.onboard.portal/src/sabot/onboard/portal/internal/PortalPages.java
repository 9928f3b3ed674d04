package sabot.onboard.portal.internal;

import static sabot.onboard.portal.internal.Html.esc;

import java.util.List;

import sabot.controlml.Role;
import sabot.onboard.config.SettingForm;
import sabot.onboard.config.TaskForm;
import sabot.onboard.portal.internal.PortalSessions.Session;

/**
 * The page's HTML, rendered on the server: every value escaped ({@link Html#esc}), no inline script or style (the
 * Content-Security-Policy allows the bundle's own {@code /static/} files only), every form that changes something
 * with the session's CSRF token.
 */
final class PortalPages {

    private PortalPages() {
    }

    private static String head(String title) {
        return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" "
                + "content=\"width=device-width, initial-scale=1\"><title>" + esc(title) + "</title>"
                + "<link rel=\"stylesheet\" href=\"/static/portal.css\"></head>";
    }

    private static String nav(String robot, Session session, Role role, String current) {
        StringBuilder sb = new StringBuilder("<header><h1>").append(esc(robot)).append("</h1><nav>");
        sb.append(link("/", "Status", current));
        if (role.includes(Role.MAINTAINER)) {
            sb.append(link("/config", "Configuration", current));
        }
        sb.append("</nav><form method=\"post\" action=\"/logout\" class=\"logout\"><input type=\"hidden\" "
                + "name=\"csrf\" value=\"").append(esc(session.csrf())).append("\"><span id=\"who\">")
                .append(esc(session.account())).append(" (").append(esc(role.label())).append(")</span> "
                        + "<button type=\"submit\" id=\"logout\">Log out</button></form></header>");
        return sb.toString();
    }

    private static String link(String href, String text, String current) {
        return "<a href=\"" + href + "\"" + (href.equals(current) ? " aria-current=\"page\"" : "") + ">" + esc(text)
                + "</a>";
    }

    static String login(String robot, String message, String account) {
        return head(robot + " — log in") + "<body class=\"login\"><main><h1>" + esc(robot) + "</h1>"
                + "<p>Log in with your XMPP account of this robot's lab (observers read, maintainers change "
                + "settings).</p>" + (message == null ? "" : "<p class=\"error\" id=\"login-error\">" + esc(message)
                        + "</p>")
                + "<form method=\"post\" action=\"/login\"><label>Account <input name=\"account\" id=\"account\" "
                + "autocomplete=\"username\" required placeholder=\"name@domain\" value=\"" + esc(account) + "\">"
                + "</label><label>Password <input name=\"password\" id=\"password\" type=\"password\" "
                + "autocomplete=\"current-password\" required></label><button type=\"submit\" id=\"login\">Log in"
                + "</button></form></main></body></html>";
    }

    /**
     * @param mapSvg the map, or null when the robot has none
     * @param pollMs the script's poll interval
     */
    static String status(String robot, Session session, Role role, String mapSvg, long pollMs) {
        StringBuilder sb = new StringBuilder(head(robot + " — status"));
        sb.append("<body data-poll=\"").append(pollMs).append("\">").append(nav(robot, session, role, "/"));
        sb.append("<main class=\"status\">");
        sb.append("<section id=\"identity\"><h2>Identity</h2><dl>");
        sb.append(row("Name", "robot-name")).append(row("JID", "robot-jid")).append(row("UUID", "robot-uuid"))
                .append(row("Page", "robot-page")).append(row("Presence", "presence")).append(row("XMPP session",
                        "online"));
        sb.append("</dl><img id=\"qr\" src=\"/qr.png\" alt=\"QR inventory (the robot's vCard photo)\" width=\"160\" "
                + "height=\"160\"></section>");
        sb.append("<section id=\"motion\"><h2>Mission and pose</h2><dl>");
        sb.append(row("Mission", "mission")).append(row("Targets", "targets")).append(row("Goal", "goal")).append(row("Pose", "pose")).append(row(
                "Velocity", "velocity")).append(row("Battery", "battery")).append(row("Updated", "updated"));
        sb.append("</dl><div class=\"map\">").append(mapSvg == null ? "<p>no map (the motion task does not run)</p>"
                : mapSvg).append("</div></section>");
        sb.append("<section id=\"tasks\"><h2>Tasks</h2><table><thead><tr><th>task</th><th>state</th></tr></thead>"
                + "<tbody id=\"task-rows\"></tbody></table></section>");
        sb.append("<section id=\"log\"><h2>Recent log</h2><pre id=\"log-lines\"></pre></section>");
        sb.append("<p id=\"stale\" class=\"error\" hidden>the page lost the robot: retrying</p>");
        sb.append("</main><script src=\"/static/portal.js\"></script></body></html>");
        return sb.toString();
    }

    private static String row(String label, String id) {
        return "<dt>" + esc(label) + "</dt><dd id=\"" + id + "\">…</dd>";
    }

    /**
     * @param message a note after a change (or null)
     * @param error   a refused change's configuration error (or null)
     */
    static String config(String robot, Session session, Role role, String file, List<TaskForm> tasks, String message,
            String error, String changedTask) {
        StringBuilder sb = new StringBuilder(head(robot + " — configuration"));
        sb.append("<body>").append(nav(robot, session, role, "/config")).append("<main class=\"config\">");
        sb.append("<p>The settings of <code>").append(esc(file)).append("</code>, checked as at start and written "
                + "back atomically. Applying restarts the task with its new settings (a task not listed in "
                + "<code>tasks</code> takes them when it is listed and the robot restarts). An empty field removes "
                + "the setting from the file: its default applies.</p>");
        if (message != null) {
            sb.append("<p class=\"ok\" id=\"config-message\">").append(esc(message)).append("</p>");
        }
        if (error != null) {
            sb.append("<p class=\"error\" id=\"config-error\">").append(esc(error)).append("</p>");
        }
        for (TaskForm task : tasks) {
            sb.append("<section class=\"task\" id=\"task-").append(esc(task.name())).append("\"><h2>").append(esc(
                    task.title())).append(" <code>").append(esc(task.name())).append("</code> ").append(task.enabled()
                            ? "<span class=\"on\">running</span>" : "<span class=\"off\">not in tasks</span>")
                    .append("</h2><p>").append(esc(task.description())).append("</p>");
            if (task.settings().isEmpty()) {
                sb.append("<p>no settings</p></section>");
                continue;
            }
            sb.append("<form method=\"post\" action=\"/config\"><input type=\"hidden\" name=\"csrf\" value=\"")
                    .append(esc(session.csrf())).append("\"><input type=\"hidden\" name=\"task\" value=\"").append(
                            esc(task.name())).append("\"><table>");
            for (SettingForm s : task.settings()) {
                String id = "f-" + task.name() + "-" + s.id();
                sb.append("<tr><th><label for=\"").append(esc(id)).append("\">").append(esc(s.name())).append(
                        "</label><br><code>").append(esc(task.name() + "." + s.id())).append("</code></th><td>");
                sb.append(input(id, s));
                sb.append("</td><td class=\"help\">").append(esc(s.description())).append("<br><small>")
                        .append(esc(constraints(s))).append("</small></td></tr>");
            }
            sb.append("</table><button type=\"submit\" id=\"apply-").append(esc(task.name())).append(
                    "\">Apply</button>").append(task.name().equals(changedTask) && error != null
                            ? " <span class=\"error\">refused: nothing was written</span>" : "")
                    .append("</form></section>");
        }
        sb.append("</main></body></html>");
        return sb.toString();
    }

    private static String input(String id, SettingForm s) {
        String name = "s." + s.id();
        String value = s.value() == null ? "" : s.value();
        if (!s.options().isEmpty() || "boolean".equals(s.type())) {
            StringBuilder sb = new StringBuilder("<select id=\"").append(esc(id)).append("\" name=\"").append(esc(name))
                    .append("\"><option value=\"\"").append(value.isEmpty() ? " selected" : "").append(">(default")
                    .append(s.defaultValue() == null ? "" : ": " + esc(shown(s.defaultValue()))).append(
                            ")</option>");
            List<SettingForm.Option> options = s.options().isEmpty() ? List.of(new SettingForm.Option("true", "true"),
                    new SettingForm.Option("false", "false")) : s.options();
            boolean listed = value.isEmpty();
            for (SettingForm.Option o : options) {
                boolean selected = o.value().equals(value);
                listed |= selected;
                sb.append("<option value=\"").append(esc(o.value())).append("\"").append(selected ? " selected" : "")
                        .append(">").append(esc(o.label())).append("</option>");
            }
            if (!listed) { // a value the file holds that is not an option (the form shows what is there)
                sb.append("<option value=\"").append(esc(value)).append("\" selected>").append(esc(value)).append(
                        "</option>");
            }
            return sb.append("</select>").toString();
        }
        return "<input id=\"" + esc(id) + "\" name=\"" + esc(name) + "\" value=\"" + esc(value) + "\" placeholder=\""
                + esc(s.defaultValue() == null ? (s.mandatory() ? "required" : "") : "default: " + shown(s
                        .defaultValue()))
                + "\"" + (s.type().equals("string") ? "" : " inputmode=\"decimal\"") + ">";
    }

    /** An empty default reads "(empty)", not as a missing one. */
    private static String shown(String defaultValue) {
        return defaultValue.isEmpty() ? "(empty)" : defaultValue;
    }

    private static String constraints(SettingForm s) {
        StringBuilder sb = new StringBuilder(s.type());
        if (s.min() != null || s.max() != null) {
            sb.append(", ").append(s.min() == null ? "…" : s.min()).append("..").append(s.max() == null ? "…" : s
                    .max());
        }
        if (s.defaultValue() != null) {
            sb.append(", default ").append(shown(s.defaultValue()));
        }
        if (s.mandatory()) {
            sb.append(", required");
        }
        return sb.toString();
    }

    /** A short page for an HTTP error. */
    static String error(int status, String reason, String detail) {
        return head(status + " " + reason) + "<body class=\"error-page\"><main><h1>" + status + " " + esc(reason)
                + "</h1><p id=\"error-detail\">" + esc(detail) + "</p><p><a href=\"/\">status page</a></p></main>"
                + "</body></html>";
    }
}
