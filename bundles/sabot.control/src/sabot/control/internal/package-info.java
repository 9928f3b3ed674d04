/** Implementations of the control laws; use {@link sabot.control.Controllers} to obtain them. */
package sabot.control.internal;
