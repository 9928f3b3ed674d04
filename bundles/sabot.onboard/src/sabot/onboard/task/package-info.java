/** The task SPI of Sabot Onboard: what a bundle provides to become a task selectable by configuration. */
package sabot.onboard.task;
