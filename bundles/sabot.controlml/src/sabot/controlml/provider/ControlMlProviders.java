package sabot.controlml.provider;

import org.jivesoftware.smack.provider.ProviderManager;

import sabot.controlml.ControlMl;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.PresenceLevelElement;

/**
 * Registers ControlML's providers with Smack's (process-wide) {@link ProviderManager}. Idempotent; called by
 * {@link sabot.controlml.ControlMlManager} before any connection uses ControlML.
 */
public final class ControlMlProviders {

    private static volatile boolean registered;

    private ControlMlProviders() {
    }

    /** Registers the IQ, extension element and error-condition providers once. */
    public static void register() {
        if (registered) {
            return;
        }
        synchronized (ControlMlProviders.class) {
            if (registered) {
                return;
            }
            ProviderManager.addIQProvider(ControlMl.ELEMENT, ControlMl.NAMESPACE, new ControlMlIQProvider());
            ProviderManager.addExtensionProvider(ControlMl.ELEMENT, ControlMl.NAMESPACE,
                    new ControlMlElementProvider());
            ProviderManager.addExtensionProvider(PresenceLevelElement.ELEMENT, ControlMl.NAMESPACE,
                    new PresenceLevelElementProvider());
            ConditionElementProvider conditions = new ConditionElementProvider();
            for (ControlMlCondition c : ControlMlCondition.values()) {
                ProviderManager.addExtensionProvider(c.element(), ControlMl.ERRORS_NAMESPACE, conditions);
            }
            registered = true;
        }
    }
}
