package sabot.workbench.joystick.internal;

import org.osgi.framework.BundleContext;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Announces the plug-in once it is installed and started (one log line: version and view). Installation tests look
 * for it after the p2 director has installed the feature; the view itself starts with the workbench page.
 */
@Component(immediate = true, service = JoystickPlugin.class)
public final class JoystickPlugin {

    @Activate
    void activate(BundleContext context) {
        LoggerFactory.getLogger("sabot.workbench.joystick").info("Sabot joystick plug-in {} active (view {})", context
                .getBundle().getVersion(), JoystickView.ID);
    }

    static Logger log() {
        return LoggerFactory.getLogger("sabot.workbench.joystick");
    }
}
