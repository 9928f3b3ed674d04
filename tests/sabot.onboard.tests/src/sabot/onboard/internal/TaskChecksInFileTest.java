package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;

import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.component.runtime.ServiceComponentRuntime;
import org.osgi.service.metatype.MetaTypeService;

/**
 * A task bundle's own settings check, found as a service the way the application finds it, reports its problem on the
 * line of the file that holds the key (the controlml task's checks, from its bundle).
 */
class TaskChecksInFileTest {

    @TempDir
    Path dir;
    Path passwordFile;

    @BeforeEach
    void privatePasswordFile() throws Exception {
        passwordFile = dir.resolve("robot.pw");
        Files.writeString(passwordFile, "s3cret\n");
        Files.setPosixFilePermissions(passwordFile, PosixFilePermissions.fromString("rw-------"));
    }

    ConfigError fileError(String text) throws Exception {
        BundleContext context = FrameworkUtil.getBundle(OnboardApplication.class).getBundleContext();
        var catalog = OsgiTaskCatalog.read(context, TaskMetatypeRangesTest.service(context, ServiceComponentRuntime.class),
                TaskMetatypeRangesTest.service(context, MetaTypeService.class));
        OnboardConfigFile c = OnboardConfigFile.parse(dir.resolve("onboard.conf"), text);
        return assertThrows(ConfigError.class, () -> TaskSettings.check(c, TaskSettings.resolve(c, catalog),
                task -> OnboardApplication.settingsChecks(context, task)));
    }

    @Test
    void sharedPasswordFileIsOneLineNamingFileLineAndKey() throws Exception {
        Files.setPosixFilePermissions(passwordFile, PosixFilePermissions.fromString("rw-r--r--"));
        ConfigError e = fileError("tasks = controlml\ncontrolml.jid = sabot-01@sabot.local\n"
                + "controlml.passwordFile = " + passwordFile + "\n");
        assertEquals(dir.resolve("onboard.conf") + ":3: key 'controlml.passwordFile': " + passwordFile
                + " is readable or writable by group or others (mode 0644); make it private: chmod 600 "
                + passwordFile, e.getMessage());
    }

    @Test
    void missingMandatorySettingIsReportedOnTheTasksLine() throws Exception {
        ConfigError e = fileError("# robot\ntasks = controlml\ncontrolml.passwordFile = " + passwordFile + "\n");
        assertEquals(dir.resolve("onboard.conf") + ":2: key 'controlml.jid': task 'controlml' needs this setting "
                + "(it has no default)", e.getMessage());
    }

    @Test
    void badJidInTheFileIsReportedOnItsLine() throws Exception {
        ConfigError e = fileError("tasks = controlml\ncontrolml.passwordFile = " + passwordFile
                + "\ncontrolml.jid = sabot-01\n");
        assertEquals(dir.resolve("onboard.conf") + ":3: key 'controlml.jid': 'sabot-01' is not a bare JID "
                + "(local@domain without a resource, e.g. sabot-01@sabot.local)", e.getMessage());
    }
}
