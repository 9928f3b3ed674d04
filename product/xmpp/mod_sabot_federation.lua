-- Sabot's federation of two private servers on loopback, for Prosody 0.12 (docs/FEDERATION.md; started by
-- sabot-xmpp start --federate). Two things Prosody has no option for:
--  * where the peer server is. mod_s2s finds a remote domain through net.resolvers.service (SRV _xmpp-server._tcp and
--    _xmpps-server._tcp, then A/AAAA), and without lua-unbound that resolver reads /etc/resolv.conf only, never
--    /etc/hosts; 0.12.3 has no static route. This module wraps the shared resolver's constructor: for a peer of
--    sabot_federation_peers it returns a resolver of the peer's address literal and port (no DNS query at all), and
--    no target for direct TLS (the peer speaks STARTTLS on its s2s port). Any other domain goes the usual way.
--  * whom to federate with. Stanzas to any domain but the peers are refused here (not-allowed), and a stream from any
--    other domain is closed (policy-violation), both logged. With s2s_secure_auth and no dialback module, a peer is
--    admitted only with a certificate of its domain signed by the CA of ssl.cafile (mod_s2s_auth_certs).
local basic = require "net.resolvers.basic";
local service = require "net.resolvers.service";
local st = require "util.stanza";

-- domain -> { address, port }; { } for a peer that DNS finds (a lab's real servers: only the filter below)
local peers = module:get_option("sabot_federation_peers", {});

-- one wrapper for every host that loads the module: the resolver table is shared by the whole server
if not service.sabot_original_new then
	service.sabot_original_new = service.new;
	local no_target = { next = function (_, cb) cb(nil); end };
	service.new = function (domain, srv, proto, extra)
		local peer = peers[domain];
		if not (peer and peer[1]) then -- a peer without an address: found by DNS, as any domain
			return service.sabot_original_new(domain, srv, proto, extra);
		elseif srv == "xmpp-server" then
			module:log("debug", "static s2s route %s -> %s:%d", domain, peer[1], peer[2]);
			return basic.new(peer[1], peer[2], proto, extra);
		elseif srv == "xmpps-server" then
			return no_target;
		end
		return service.sabot_original_new(domain, srv, proto, extra);
	end
end

function module.unload()
	if service.sabot_original_new then
		service.new, service.sabot_original_new = service.sabot_original_new, nil;
	end
end

module:hook("route/remote", function (event)
	if peers[event.to_host] then return; end
	module:log("warn", "refused a stanza to %s: not a federation peer of %s", event.to_host, module.host);
	module:send(st.error_reply(event.stanza, "cancel", "not-allowed",
		"this server federates with its lab's peer domain only"));
	return true;
end, 100);

module:hook("s2s-stream-features", function (event)
	local from = event.origin.from_host;
	if peers[from] then return; end
	module:log("warn", "closed an incoming s2s stream from %s: not a federation peer of %s", tostring(from), module.host);
	event.origin:close({ condition = "policy-violation", text = "this server federates with its lab's peer domain only" });
end, 1000);
