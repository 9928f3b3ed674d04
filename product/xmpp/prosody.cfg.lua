-- Private, loopback-only Prosody 0.12 instance for Sabot, started by product/bin/sabot-xmpp (behind ./sabot xmpp,
-- ./sabot demo and the JUnit fixture sabot.testsupport.xmpp.PrivateXmppServer). Never start Prosody without --config
-- pointing here.
-- Everything comes from the environment (Prosody's ENV_<name> globals; Lua's os.getenv is not reachable):
--   SABOT_XMPP_RUN        absolute state directory (a relative one makes Prosody 0.12.3 hang on start)
--   SABOT_XMPP_CONFIG     the folder of this file (Sabot's modules are beside it)
--   SABOT_GROUP_ENROLLING the shared group of the robots asking for access (product/bin/lib.sh)
--   SABOT_C2S_PORT        client port on 127.0.0.1 (default 15222)
--   SABOT_RUN_AS_ROOT=1   needed when started by root, or Prosody refuses and hangs
--   SABOT_ARCHIVE_STORE   "memory" for tests (the file archive caps a chatting pair at ~600 msgs/s)
--   SABOT_DOMAIN, SABOT_DOMAIN2  the two virtual hosts (default sabot.local, sabot2.local)
--   SABOT_TLS             "required" (the default): clients must STARTTLS, with the certificates sabot-xmpp made
--                         in $SABOT_XMPP_RUN/certs (signed by the lab CA of $SABOT_XMPP_RUN/ca); "off": plain TCP, for
--                         the benchmark that compares the two only
--   SABOT_XMPP_S2S_PORT, SABOT_XMPP_PEER  a federation's Prosody (sabot-xmpp start --federate, docs/FEDERATION.md):
--                         its s2s port on 127.0.0.1, and the one peer, "DOMAIN=ADDRESS:PORT"; it serves SABOT_DOMAIN
--                         only, and federates with the peer only, over TLS with certificates of the lab CA
local run = ENV_SABOT_XMPP_RUN or error("SABOT_XMPP_RUN is not set")
local c2s_port = (ENV_SABOT_C2S_PORT or "15222") + 0

run_as_root = (ENV_SABOT_RUN_AS_ROOT == "1")
data_path = run .. "/data"
pidfile   = run .. "/prosody.pid"
certificates = run .. "/certs"
local tls = (ENV_SABOT_TLS or "required") ~= "off"
log = { { levels = { min = ENV_SABOT_XMPP_LOGLEVEL or "info" }, to = "file", filename = run .. "/prosody.log" } }

-- loopback only, non-default port, no s2s, no http
interfaces = { "127.0.0.1" }
local_interfaces = { "127.0.0.1" }
c2s_ports = { c2s_port }
c2s_direct_tls_ports = { }
legacy_ssl_ports = { }
s2s_direct_tls_ports = { }
local federation = ENV_SABOT_XMPP_S2S_PORT ~= nil
if federation then
    local peer, address, port = (ENV_SABOT_XMPP_PEER or ""):match("^([%w.-]+)=([%d.]+):(%d+)$")
    if not peer then error("SABOT_XMPP_PEER is not DOMAIN=ADDRESS:PORT: " .. tostring(ENV_SABOT_XMPP_PEER)) end
    s2s_ports = { ENV_SABOT_XMPP_S2S_PORT + 0 }
    modules_disabled = { }
    -- s2s: TLS required, and a peer authenticated by its certificate only (no dialback module is loaded)
    s2s_require_encryption = true
    s2s_secure_auth = true
    ssl = { cafile = run .. "/ca/ca.pem" }  -- the lab CA: the only one a peer's certificate may be signed by
    sabot_federation_peers = { [peer] = { address, port + 0 } }  -- mod_sabot_federation
else
    s2s_ports = { }
    modules_disabled = { "s2s", "s2s_auth_certs" }
    s2s_require_encryption = false
end

c2s_require_encryption = tls
-- PLAIN never without TLS: on a plain stream (SABOT_TLS=off) only SCRAM, which does not send the password
allow_unencrypted_plain_auth = false
authentication = "internal_hashed"
-- accounts stored as SCRAM-SHA-256 keys: the server then offers SCRAM-SHA-256 (and -PLUS on TLS 1.2), not SHA-1
password_hash = "SHA-256"
storage = { archive = ENV_SABOT_ARCHIVE_STORE or "internal" }

-- Prosody defaults to Nagle on; with delayed ACKs that costs ~40 ms per request on loopback
network_settings = { nagle = false }

-- Lua 5.4's generational collector instead of Prosody's default (incremental, pause 105 %: collecting almost all
-- the time). Stanzas are short-lived tables; profiled under the ControlML benchmark, the incremental sweep alone was
-- ~17 % of Prosody's CPU. Measured (./sabot bench controlml, docs/CONTROLML.md section 12): server CPU per round trip
-- -30 to -40 %, 100 robots x 10 Hz telemetry at 35-39 % CPU instead of 59-76 %, telemetry p99 25-34 ms instead of
-- 56-145 ms. Needs Lua 5.4 (Prosody refuses the setting on older Lua).
gc = { mode = "generational" }

-- XEP-0077 in-band registration closed: accounts are made by the lab's administrator (sabot-xmpp register, and
-- enrol token for a robot); a logged-in account may still change its password (a robot replaces its enrolment token)
allow_registration = false

-- XEP-0313 MAM: archive chat by default
default_archive_policy = true
archive_expires_after = "1d"
max_archive_query_results = 250

-- XEP-0198 stream management: sessions survive a dropped socket this long
smacks_hibernation_time = 60

-- The lab's shared groups (sabot-xmpp group add|remove): public groups, so that every account's roster holds their
-- members under the group's name; a robot reads its requesters' roles there (docs/SECURITY.md), a workbench its robots.
groups_file = run .. "/groups.txt"
-- the quarantine of robots enrolled and not yet approved (mod_sabot_quarantine, beside this file: it sees no group)
plugin_paths = { ENV_SABOT_XMPP_CONFIG or error("SABOT_XMPP_CONFIG (the folder of this file) is not set") }
sabot_quarantine_group = ENV_SABOT_GROUP_ENROLLING or error("SABOT_GROUP_ENROLLING is not set")

-- built in a local and assigned once: a Prosody config file cannot read back an option it has set
local modules = {
    "roster"; "saslauth"; "disco"; "ping"; "time"; "version"; "uptime";
    "private"; "blocklist"; "carbons";
    "register";      -- XEP-0077: password change only (allow_registration is false)
    "pep";           -- XEP-0163
    "vcard";         -- XEP-0054 vcard-temp, stored verbatim (vcard_legacy converts to vCard4 and drops
                     -- DESC, ROLE, GEO...: device identity needs every field back as it was written)
    "mam";           -- XEP-0313
    "smacks";        -- XEP-0198
    "offline";       -- XEP-0160 offline storage with XEP-0203 delay stamps
    "groups";        -- the lab's shared groups (roles, robots) from groups_file, written into every roster
    "sabot_quarantine"; -- a robot asking for access sees no group (mod_sabot_quarantine.lua, beside this file)
    "admin_shell";   -- prosodyctl shell on data_path/prosody.sock: sabot-xmpp group applies group changes live
}
if tls then table.insert(modules, "tls") end
if federation then table.insert(modules, "sabot_federation") end -- the peer's route, and no other domain
modules_enabled = modules

VirtualHost (ENV_SABOT_DOMAIN or "sabot.local")
if not federation then
    VirtualHost (ENV_SABOT_DOMAIN2 or "sabot2.local")   -- second domain for cross-domain tests
end

-- XEP-0045 rooms: the fleet lobby where online devices are discovered (sabot.fleet, roster rule 11)
Component ("conference." .. (ENV_SABOT_DOMAIN or "sabot.local")) "muc"
    -- every occupant's real JID shown from the room's making on, whoever makes it (sabot.fleet.FleetLobby also asks
    -- for it when it makes the room): the lobby's purpose is to say who is online
    muc_room_default_public_jids = true
