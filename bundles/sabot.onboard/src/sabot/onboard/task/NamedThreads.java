package sabot.onboard.task;

import java.util.concurrent.ThreadFactory;

/** Thread factories of the onboard tasks (for every task bundle): every thread is named (a stack dump says which task it is) and a daemon. */
public final class NamedThreads {

    private NamedThreads() {
    }

    /** @return a factory of daemon threads called {@code name} */
    public static ThreadFactory daemon(String name) {
        return daemon(name, Thread.NORM_PRIORITY);
    }

    /** @return a factory of daemon threads called {@code name} with a priority (the control loop's is the highest) */
    public static ThreadFactory daemon(String name, int priority) {
        return r -> {
            Thread t = new Thread(r, name);
            t.setDaemon(true);
            t.setPriority(priority);
            return t;
        };
    }
}
