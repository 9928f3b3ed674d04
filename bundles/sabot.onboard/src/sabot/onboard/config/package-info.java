/**
 * The robot's configuration file as a service, for tools that show and change it while the robot runs (the robot's
 * web page): every installed task's settings as its Metatype describes them, and a change checked with the same rules
 * and the same error texts as the file at start, written back atomically and applied through Config Admin. Provided
 * by the onboard application once the file has been read.
 */
package sabot.onboard.config;
