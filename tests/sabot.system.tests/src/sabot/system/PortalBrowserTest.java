package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.File;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.MessageDigest;
import java.security.cert.CertificateFactory;
import java.time.Duration;
import java.util.Base64;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.impl.JidCreate;
import org.openqa.selenium.By;
import org.openqa.selenium.JavascriptExecutor;
import org.openqa.selenium.OutputType;
import org.openqa.selenium.StaleElementReferenceException;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.WebElement;
import org.openqa.selenium.chrome.ChromeDriver;
import org.openqa.selenium.chrome.ChromeDriverService;
import org.openqa.selenium.chrome.ChromeOptions;

import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.Goal;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The robot's web page in a real browser: Chromium from Debian (headless) driven by Selenium, on the product driving
 * the simulated robot, over HTTPS with the lab CA's certificate (its key pinned in the browser: no blanket exception).
 * A maintainer logs in, sees the pose change while the robot drives, changes a setting (applied, in the file), is
 * refused a bad value with the configuration's error text (the file unchanged) and a forged change without the CSRF
 * token, logs out; an observer reads and cannot change anything. Screenshots go to docs/images/portal-*.png.
 */
class PortalBrowserTest extends RigTest {

    static final Path CHROMIUM = Path.of("/usr/bin/chromium");
    static final Path CHROMEDRIVER = Path.of("/usr/bin/chromedriver");
    static final Path IMAGES = PrivateXmppServer.repositoryRoot().resolve("docs/images");

    /** Waits until {@code condition} holds, reading the page every 50 ms (the page changes by itself). */
    static void await(Supplier<Boolean> condition, long seconds, String what) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(seconds);
        while (!Boolean.TRUE.equals(condition.get())) {
            if (System.nanoTime() > deadline) {
                throw new AssertionError("the page did not show " + what + " within " + seconds + " s");
            }
            TimeUnit.MILLISECONDS.sleep(50);
        }
    }

    /**
     * @return the text of the element {@code id} of the page shown now, "" while the page has none (or is replaced
     *         while read)
     */
    static String textOf(WebDriver b, String id) {
        try {
            List<WebElement> found = b.findElements(By.id(id));
            return found.isEmpty() ? "" : found.get(0).getText();
        } catch (StaleElementReferenceException e) {
            return "";
        }
    }

    /** @return the text of the element {@code id} once the page that a click submitted shows it */
    static String shown(WebDriver b, String id) throws InterruptedException {
        await(() -> !b.findElements(By.id(id)).isEmpty(), 10, "#" + id);
        return b.findElement(By.id(id)).getText();
    }

    static void screenshot(WebDriver browser, String name) throws Exception {
        Files.createDirectories(IMAGES);
        Files.write(IMAGES.resolve("portal-" + name + ".png"), ((ChromeDriver) browser).getScreenshotAs(OutputType
                .BYTES));
    }

    /** @return base64 of the SHA-256 of the certificate's public key: Chromium's pin for exactly this certificate */
    static String spkiPin(Path certificate) throws Exception {
        try (InputStream in = Files.newInputStream(certificate)) {
            byte[] spki = CertificateFactory.getInstance("X.509").generateCertificate(in).getPublicKey().getEncoded();
            return Base64.getEncoder().encodeToString(MessageDigest.getInstance("SHA-256").digest(spki));
        }
    }

    static void logIn(WebDriver b, String base, String account) {
        b.get(base + "/");
        assertTrue(b.getCurrentUrl().endsWith("/login"), b.getCurrentUrl());
        b.findElement(By.id("account")).sendKeys(account);
        b.findElement(By.id("password")).sendKeys(PrivateXmppServer.DEFAULT_PASSWORD);
        b.findElement(By.id("login")).click();
    }

    /** A POST from the page's own origin, with the session's cookie and without the CSRF token: its status. */
    static long forgedPost(WebDriver b) {
        return (Long) ((JavascriptExecutor) b).executeAsyncScript("var done = arguments[arguments.length - 1];"
                + "fetch('/config', {method: 'POST', headers: {'Content-Type': 'application/x-www-form-urlencoded'},"
                + " body: 'task=remotefs&s.readOnly=false'}).then(function (r) { done(r.status); });");
    }

    @Test
    void aMaintainerAndAnObserverUseTheRobotsPageInChromium(@TempDir Path dir) throws Exception {
        assertTrue(Files.isExecutable(CHROMIUM) && Files.isExecutable(CHROMEDRIVER),
                "chromium and chromium-driver are not installed (./sabot deps)");
        int port = PortalTest.freePort();
        try (RobotRig rig = RobotRig.start(xmpp, dir, CORRIDOR_WEST, new String[0], PortalTest.portalConfig(xmpp,
                port))) {
            String base = "https://127.0.0.1:" + port;
            rig.onboard.await(l -> l.contains("portal task started"), "serving its page");
            xmpp.login("observer");
            xmpp.grant(JidCreate.bareFrom("observer@" + PrivateXmppServer.DOMAIN), Role.OBSERVER);
            ChromeOptions options = new ChromeOptions();
            options.setBinary(CHROMIUM.toFile());
            options.addArguments("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                    "--window-size=1280,900", "--user-data-dir=" + Files.createDirectories(dir.resolve("chromium")),
                    "--ignore-certificate-errors-spki-list=" + spkiPin(xmpp.runDir().resolve("certs/localhost.crt")));
            ChromeDriverService service = new ChromeDriverService.Builder().usingDriverExecutable(CHROMEDRIVER
                    .toFile()).usingAnyFreePort().withLogFile(new File(dir.resolve("chromedriver.log").toString()))
                    .build();
            WebDriver b = new ChromeDriver(service, options);
            try {
                b.manage().timeouts().scriptTimeout(Duration.ofSeconds(10));
                Path conf = rig.onboard.config();

                // the maintainer logs in and sees the robot drive
                b.get(base + "/");
                screenshot(b, "login");
                logIn(b, base, RobotRig.OPERATOR + "@" + PrivateXmppServer.DOMAIN);
                WebElement robot = b.findElement(By.id("robot"));
                await(() -> robot.getAttribute("data-x") != null, 10, "the robot on the map");
                double x0 = Double.parseDouble(robot.getAttribute("data-x"));
                var goal = rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(8.0, 1.0, 0), 0.15, 0.3));
                assertTrue(goal.isSuccess(), "goal refused: " + goal.errorOrNull());
                await(() -> Double.parseDouble(robot.getAttribute("data-x")) > x0 + 0.5, 30,
                        "the robot 0.5 m further east");
                assertTrue(b.findElement(By.id("mission")).getText().startsWith("running"), b.findElement(By.id(
                        "mission")).getText());
                screenshot(b, "status");

                // a setting changed: applied and in the file
                b.findElement(By.linkText("Configuration")).click();
                b.findElement(By.cssSelector("#f-remotefs-readOnly option[value='true']")).click();
                b.findElement(By.id("apply-remotefs")).click();
                assertTrue(shown(b, "config-message").contains("task 'remotefs' restarts with its new settings"));
                assertTrue(Files.readString(conf).contains("\nremotefs.readOnly = true\n"));
                rig.onboard.await(l -> l.contains("remote FS task started") && l.contains("read-only"),
                        "restarting remotefs read-only");
                screenshot(b, "config");
                ((JavascriptExecutor) b).executeScript("arguments[0].scrollIntoView()", b.findElement(By.id(
                        "task-remotefs")));
                screenshot(b, "config-remotefs");

                // a bad value: the configuration's error text, nothing written
                byte[] before = Files.readAllBytes(conf);
                WebElement chunk = b.findElement(By.id("f-remotefs-maxChunk"));
                chunk.clear();
                chunk.sendKeys("0");
                b.findElement(By.id("apply-remotefs")).click();
                String error = shown(b, "config-error");
                assertTrue(error.endsWith("key 'remotefs.maxChunk': '0' is below the minimum 1"), error);
                screenshot(b, "config-refused");
                assertEquals(403, forgedPost(b), "a change without the CSRF token");
                assertTrue(java.util.Arrays.equals(before, Files.readAllBytes(conf)), "the file changed");

                // log-out
                b.findElement(By.id("logout")).click(); // a form's POST: the click returns before its redirect
                await(() -> b.getCurrentUrl().endsWith("/login"), 10, "the log-in page after the log-out");
                b.get(base + "/");
                assertTrue(b.getCurrentUrl().endsWith("/login"), "still logged in: " + b.getCurrentUrl());

                // the observer reads, cannot change anything
                logIn(b, base, "observer@" + PrivateXmppServer.DOMAIN);
                // the log-in form's POST: the click returns before the status page replaces the form
                await(() -> textOf(b, "who").contains("(observer)"), 10, "the observer");
                assertTrue(b.findElements(By.linkText("Configuration")).isEmpty());
                assertEquals(403, forgedPost(b));
                b.get(base + "/config");
                assertTrue(b.findElement(By.id("error-detail")).getText().contains("the configuration is for "
                        + "maintainers"), b.getPageSource());
                screenshot(b, "observer-refused");
                assertTrue(java.util.Arrays.equals(before, Files.readAllBytes(conf)), "the file changed");
                assertFalse(b.getPageSource().contains("config-message"));
            } finally {
                b.quit();
            }
        }
    }
}
