-- Sabot's enrolment quarantine for Prosody 0.12 (docs/SECURITY.md, "Enrolment"): an account in the quarantine group
-- (sabot_quarantine_group, default "sabot-enrolling": a robot enrolled with a token and not yet approved) sees no
-- shared group in its roster. mod_groups makes every public group part of every roster, the robots' and the roles'
-- too; this hook runs after mod_groups' (a lower priority) and takes what mod_groups injected (persist == false) out
-- of a quarantined account's roster. A robot reads its requesters' roles in its roster, so a quarantined robot finds
-- no role anywhere and refuses every request; the others still see it, under the quarantine group's name: that is
-- how a workbench lists the robots asking for access. ejabberd does the same with its shared groups' display lists
-- (product/bin/sabot-xmpp).
local groups_file = module:get_option_path("groups_file", nil, "config");
local quarantine = module:get_option_string("sabot_quarantine_group", "sabot-enrolling");

-- The members of the quarantine group, read from the groups file at each roster load: sabot-xmpp changes the file,
-- then reloads the online rosters, and a fresh read here is what they must see.
local function quarantined()
	local members, current = {}, nil;
	if not groups_file then return members; end
	local file = io.open(groups_file);
	if not file then return members; end
	for line in file:lines() do
		local name = line:match("^%s*%[%+?(.-)%]%s*$");
		if name then
			current = name;
		elseif current == quarantine and line:match("%S") then
			members[(line:match("^%s*([^=%s]+)"))] = true;
		end
	end
	file:close();
	return members;
end

module:hook("roster-load", function (event)
	local roster = event.roster;
	if not roster or not quarantined()[event.username .. "@" .. event.host] then return; end
	for jid, item in pairs(roster) do
		if jid and item.persist == false then roster[jid] = nil; end
	end
end, -10);
