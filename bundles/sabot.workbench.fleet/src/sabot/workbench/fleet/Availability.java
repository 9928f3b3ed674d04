package sabot.workbench.fleet;

/** A robot's presence level as the workbench sees it (docs/CONTROLML.md section 7), plus offline. */
public enum Availability {
    /** no available presence from the robot (never seen, or it went away) */
    OFFLINE,
    /** online and idle: free for a mission */
    FREE,
    /** online, a mission is running or paused */
    BUSY,
    /** online, in maintenance mode or after a fault */
    AWAY;

    /** @return the name an operator reads, e.g. {@code Free} */
    public String label() {
        return name().charAt(0) + name().substring(1).toLowerCase(java.util.Locale.ROOT);
    }
}
