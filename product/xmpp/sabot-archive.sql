-- The archive of every ControlML stanza (docs/ARCHIVE.md): one row per stanza a client sent through the server,
-- written by the ejabberd module mod_sabot_archive.erl, read by ./sabot log. Loaded by product/bin/sabot-xmpp into
-- the private PostgreSQL's database "ejabberd" after ejabberd's own schema (pg.new.sql).
CREATE TABLE IF NOT EXISTS sabot_archive (
    seq         bigserial PRIMARY KEY,
    at          timestamptz NOT NULL,            -- when the server took the stanza from its sender
    server_host text NOT NULL,                   -- the sender's virtual host (sabot.local)
    node        text NOT NULL,                   -- the ejabberd node that took it (a cluster's nodes share the table)
    kind        text NOT NULL,                   -- get, set, result, error, telemetry
    via         text NOT NULL,                   -- iq (a request or answer), message (stored for an offline
                                                 -- device), pep (a telemetry publication)
    res         text NOT NULL,                   -- the ControlML resource: cm.goal, cm.position, ...
    cm_id       text NOT NULL,                   -- the control-ml element's id (YYYYMMDD:UINT32)
    stanza_id   text NOT NULL,                   -- the stanza's id (an IQ answer has its request's)
    device      text NOT NULL,                   -- bare JID of the resource's owner: a request's recipient, an
                                                 -- answer's or a publication's sender
    sender      text NOT NULL,                   -- full JID
    recipient   text NOT NULL,                   -- full JID (bare for a stored command or a publication)
    condition   text NOT NULL,                   -- an error's condition (ControlML's, else the stanza error's)
    text        text NOT NULL,                   -- an error's text
    xml         text NOT NULL                    -- the control-ml element as sent
);
CREATE INDEX IF NOT EXISTS sabot_archive_device_at ON sabot_archive (device, at);
CREATE INDEX IF NOT EXISTS sabot_archive_at ON sabot_archive (at);
CREATE INDEX IF NOT EXISTS sabot_archive_answer ON sabot_archive (device, cm_id); -- an answer to its request

-- A request with its answer: the device's result or error with the request's ControlML id, to the requester's
-- account, by the same way (an IQ answers an IQ; a stored command is answered by a message). What ./sabot log and
-- the command history (urn:sabot:archive:1, mod_sabot_archive.erl) read.
CREATE OR REPLACE VIEW sabot_requests AS
SELECT r.seq, r.at, r.device, r.kind, r.via, r.res, r.cm_id, r.sender, r.recipient, r.xml,
       a.kind AS answer, coalesce(a.condition, '') AS condition, coalesce(a.text, '') AS text,
       round((extract(epoch FROM a.at - r.at) * 1000)::numeric, 1) AS answer_ms
FROM sabot_archive r
LEFT JOIN LATERAL (
    SELECT a.kind, a.condition, a.text, a.at FROM sabot_archive a
    WHERE a.device = r.device AND a.cm_id = r.cm_id AND a.via = r.via AND a.kind IN ('result', 'error')
      AND split_part(a.recipient, '/', 1) = split_part(r.sender, '/', 1) AND a.at >= r.at
    ORDER BY a.at LIMIT 1) a ON true
WHERE r.kind IN ('get', 'set');

-- An operator's commands: the sets, without telemetry leases (cm.telemetry, docs/CONTROLML.md section 6), which a
-- workbench renews every 15 s for each robot it shows. The command history and ./sabot log list these.
CREATE OR REPLACE VIEW sabot_commands AS
SELECT * FROM sabot_requests WHERE kind = 'set' AND res <> 'cm.telemetry';
