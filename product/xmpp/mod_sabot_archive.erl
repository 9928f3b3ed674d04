%%% The archive of every ControlML stanza, in the server's SQL database (docs/ARCHIVE.md): an ejabberd 23.01 module
%%% that Sabot's private server loads with --archive sql (product/bin/sabot-xmpp compiles it into DIR/ebin).
%%%
%%% MAM (XEP-0313) archives messages; ControlML requests and answers are IQs, and telemetry is PEP publications, so
%%% neither reaches MAM. This module sees every stanza a client of this node sends (the user_send_packet hook): a
%%% request (get or set), its answer (result or error), a command stored for an offline device (a message), and a
%%% telemetry publication (an IQ set publishing to a urn:sabot:controlml:1:telemetry:* node). Each becomes one row of
%%% the table sabot_archive (schema: product/xmpp/sabot-archive.sql). Every node of a cluster archives what its own
%%% clients send, into the one database.
%%%
%%% The hook only hands the row to this host's archiver process (a cast: the client's session never waits on the
%%% database); the archiver writes the rows it holds in one multi-row INSERT every ?FLUSH_MS or when ?BATCH rows
%%% wait. A failed write keeps the rows for the next attempt (logged once per failure streak), up to ?MAX_HELD rows;
%%% beyond that the oldest are dropped and counted in the log. Rows older than the option retention_days are
%%% deleted at start and every hour.
%%%
%%% It also answers the command history of a device (urn:sabot:archive:1, docs/ARCHIVE.md): an IQ get to the server's
%%% domain from an account in one of the groups of the option readers (the lab's roles), answered from the view
%%% sabot_requests after every node's archiver has written what it held; and a device's statistics over a window
%%% (the same namespace, the same readers: docs/STATISTICS.md), from the same table and view.
-module(mod_sabot_archive).
-behaviour(gen_mod).
-behaviour(gen_server).

-export([start/2, stop/1, reload/3, depends/2, mod_options/1, mod_opt_type/1, mod_doc/0]).
-export([start_link/2, user_send_packet/1, process_iq/1, decode_iq_subel/1]).
-export([init/1, handle_call/3, handle_cast/2, handle_info/2, terminate/2, code_change/3]).

-include("logger.hrl").
-include("xmpp.hrl").

-define(NS_CONTROLML, <<"urn:sabot:controlml:1">>).
-define(NS_CONTROLML_ERRORS, <<"urn:sabot:controlml:1:errors">>).
-define(NS_ARCHIVE, <<"urn:sabot:archive:1">>).
-define(HISTORY_MAX, 500).
-define(HISTORY_DEFAULT, 50).
-define(STATISTICS_MAX_S, 604800). % a week: the archive keeps 30 days by default, a window is a recent one
-define(STATISTICS_DEFAULT_S, 900).
-define(TELEMETRY_NODE_PREFIX, <<"urn:sabot:controlml:1:telemetry:">>).
-define(FLUSH_MS, 200).
-define(BATCH, 1000).
-define(MAX_HELD, 200000).
-define(PURGE_MS, 3600000).

-record(state, {host, rows = [], held = 0, dropped = 0, failing = false, timer}).

%%% --- gen_mod ------------------------------------------------------------------------------------------------------
start(Host, Opts) ->
    gen_mod:start_child(?MODULE, Host, Opts).

stop(Host) ->
    gen_mod:stop_child(?MODULE, Host).

reload(_Host, _NewOpts, _OldOpts) ->
    ok.

depends(_Host, _Opts) ->
    [].

mod_opt_type(retention_days) ->
    econf:pos_int();
mod_opt_type(readers) ->
    econf:list(econf:binary()).

mod_options(_Host) ->
    [{retention_days, 30}, {readers, []}].

mod_doc() ->
    #{desc => ["Archives every ControlML stanza (Sabot) in the SQL table sabot_archive."]}.

start_link(Host, Opts) ->
    gen_server:start_link({local, gen_mod:get_module_proc(Host, ?MODULE)}, ?MODULE, [Host, Opts], []).

%%% --- the hook -----------------------------------------------------------------------------------------------------
%% Runs in the sending client's session: never fails, never waits.
user_send_packet({Packet, #{lserver := Host, jid := Jid}} = Acc) ->
    try row(with_from(Packet, Jid)) of
        none -> ok;
        Row -> gen_server:cast(gen_mod:get_module_proc(Host, ?MODULE), {row, Row})
    catch
        Class:Reason -> ?ERROR_MSG("Sabot archive: a stanza not archived (~p:~p): ~ts",
                                   [Class, Reason, fxml:element_to_binary(xmpp:encode(Packet))])
    end,
    Acc;
user_send_packet(Acc) ->
    Acc.

with_from(Packet, Jid) ->
    case xmpp:get_from(Packet) of
        undefined -> xmpp:set_from(Packet, Jid);
        _ -> Packet
    end.

%% The row of a stanza: {At, Kind, Via, Res, CmId, StanzaId, Device, Sender, Recipient, Condition, Text, Xml}, or none.
%% Device is the bare JID of the side whose resource it is: the recipient of a request, the sender of an answer or
%% of telemetry.
row(#iq{type = Type, id = Id, from = From, to = To, sub_els = Els}) ->
    Recipient = recipient(From, To),
    case controlml(Els) of
        {ok, Cm} ->
            Kind = iq_kind(Type, Cm),
            {Condition, Text} = condition(Type, Els),
            make_row(Kind, <<"iq">>, attr(<<"res">>, Cm), attr(<<"id">>, Cm), Id, device(Kind, From, Recipient),
                     From, Recipient, Condition, Text, Cm);
        none when Type == set ->
            case telemetry(Els) of
                {ok, Node, Cm} ->
                    Res = binary:part(Node, byte_size(?TELEMETRY_NODE_PREFIX),
                                      byte_size(Node) - byte_size(?TELEMETRY_NODE_PREFIX)),
                    make_row(<<"telemetry">>, <<"pep">>, Res, attr(<<"id">>, Cm), Id, bare(From), From, Recipient,
                             <<>>, <<>>, Cm);
                none -> none
            end;
        none -> none
    end;
row(#message{id = Id, from = From, to = To, sub_els = Els}) ->
    case controlml(Els) of
        {ok, Cm} ->
            Recipient = recipient(From, To),
            Kind = attr(<<"type">>, Cm),
            make_row(Kind, <<"message">>, attr(<<"res">>, Cm), attr(<<"id">>, Cm), Id,
                     device(Kind, From, Recipient), From, Recipient, <<>>, <<>>, Cm);
        none -> none
    end;
row(_) ->
    none.

make_row(Kind, Via, Res, CmId, StanzaId, Device, From, Recipient, Condition, Text, Cm) ->
    {os:system_time(microsecond), Kind, Via, Res, CmId, StanzaId, Device, jid:encode(From), jid:encode(Recipient),
     Condition, Text, fxml:element_to_binary(Cm)}.

%% A stanza without 'to' goes to the sender's own account (a PEP publication).
recipient(From, undefined) -> jid:remove_resource(From);
recipient(_From, To) -> To.

iq_kind(error, _Cm) -> <<"error">>;
iq_kind(result, _Cm) -> <<"result">>;
iq_kind(Type, Cm) ->
    case attr(<<"type">>, Cm) of
        <<>> -> atom_to_binary(Type, utf8);
        T -> T
    end.

device(Kind, _From, Recipient) when Kind == <<"get">>; Kind == <<"set">> -> bare(Recipient);
device(_Kind, From, _Recipient) -> bare(From).

bare(Jid) -> jid:encode(jid:remove_resource(Jid)).

controlml(Els) ->
    case [E || E <- [element(El) || El <- Els], is_controlml(E)] of
        [Cm | _] -> {ok, Cm};
        [] -> none
    end.

is_controlml(#xmlel{name = <<"control-ml">>} = El) -> fxml:get_tag_attr_s(<<"xmlns">>, El) == ?NS_CONTROLML;
is_controlml(_) -> false.

%% The ControlML payload of a publication to a telemetry node: {ok, Node, ControlMl} or none.
telemetry(Els) ->
    case [E || E <- [element(El) || El <- Els], E#xmlel.name == <<"pubsub">>,
               fxml:get_tag_attr_s(<<"xmlns">>, E) == ?NS_PUBSUB] of
        [PubSub | _] ->
            case fxml:get_subtag(PubSub, <<"publish">>) of
                false -> none;
                Publish ->
                    Node = fxml:get_tag_attr_s(<<"node">>, Publish),
                    case binary:longest_common_prefix([Node, ?TELEMETRY_NODE_PREFIX])
                         == byte_size(?TELEMETRY_NODE_PREFIX) of
                        true ->
                            Payloads = [P || #xmlel{name = <<"item">>} = I <- Publish#xmlel.children,
                                             #xmlel{} = P <- I#xmlel.children, is_controlml(P)],
                            case Payloads of
                                [Cm | _] -> {ok, Node, Cm};
                                [] -> none
                            end;
                        false -> none
                    end
            end;
        [] -> none
    end.

%% An error's condition: the ControlML one (urn:sabot:controlml:1:errors) if any, else the stanza error's; and its
%% text.
condition(error, Els) ->
    case [E || E <- [element(El) || El <- Els], E#xmlel.name == <<"error">>] of
        [Error | _] ->
            Children = [C || #xmlel{} = C <- Error#xmlel.children],
            Own = [C#xmlel.name || C <- Children, fxml:get_tag_attr_s(<<"xmlns">>, C) == ?NS_CONTROLML_ERRORS],
            Stanza = [C#xmlel.name || C <- Children, C#xmlel.name /= <<"text">>,
                                      fxml:get_tag_attr_s(<<"xmlns">>, C) == ?NS_STANZAS],
            Text = case [C || C <- Children, C#xmlel.name == <<"text">>] of
                       [T | _] -> fxml:get_tag_cdata(T);
                       [] -> <<>>
                   end,
            {case Own ++ Stanza of [C | _] -> C; [] -> <<>> end, Text};
        [] -> {<<>>, <<>>}
    end;
condition(_Type, _Els) ->
    {<<>>, <<>>}.

%% A sub-element as XML: the session leaves unknown ones as #xmlel{}, known ones may be records.
element(#xmlel{} = El) -> El;
element(Record) -> xmpp:encode(Record).

attr(Name, El) -> fxml:get_tag_attr_s(Name, El).

%%% --- the command history ---------------------------------------------------------------------------------------
%% <history xmlns='urn:sabot:archive:1' device='BARE JID' [max='1..500'] [before='SEQ']/>: the device's commands (sets),
%% newest first (by the time the server took them: a cluster's nodes number their rows as each writes them), each with
%% its answer.

%% The request reaches process_iq as XML (ejabberd's codec does not know the element).
decode_iq_subel(El) ->
    El.

process_iq(#iq{type = set, lang = Lang} = IQ) ->
    xmpp:make_error(IQ, xmpp:err_not_allowed(<<"the archive is read with a get">>, Lang));
process_iq(#iq{type = get, from = From, to = To, lang = Lang, sub_els = [El]} = IQ) ->
    Host = To#jid.lserver,
    Readers = gen_mod:get_module_opt(Host, ?MODULE, readers),
    Groups = mod_shared_roster:list_groups(Host), % a group not made yet holds nobody (and would crash the check)
    case lists:any(fun(G) -> lists:member(G, Groups) andalso
                                 mod_shared_roster:is_user_in_group({From#jid.luser, From#jid.lserver}, G, Host)
                   end, Readers) of
        false ->
            xmpp:make_error(IQ, xmpp:err_forbidden(
                iolist_to_binary([<<"the archive is for the lab's roles (the groups ">>,
                                  lists:join(<<", ">>, Readers), <<")">>]), Lang));
        true when is_record(El, xmlel), El#xmlel.name == <<"statistics">> ->
            statistics(IQ, Host, El, Lang);
        true ->
            case history_query(element(El)) of
                {error, Text} ->
                    xmpp:make_error(IQ, xmpp:err_bad_request(Text, Lang));
                {ok, Device, Query} ->
                    flush_cluster(Host),
                    case ejabberd_sql:sql_query(Host, Query) of
                        {selected, _Columns, Rows} ->
                            xmpp:make_iq_result(IQ, #xmlel{name = <<"history">>,
                                                           attrs = [{<<"xmlns">>, ?NS_ARCHIVE}, {<<"device">>, Device}],
                                                           children = [command(Row) || Row <- Rows]});
                        Error ->
                            ?ERROR_MSG("Sabot archive: the history of ~ts not read: ~p", [Device, Error]),
                            xmpp:make_error(IQ, xmpp:err_internal_server_error(<<"the archive could not be read">>,
                                                                               Lang))
                    end
            end
    end;
process_iq(#iq{lang = Lang} = IQ) ->
    xmpp:make_error(IQ, xmpp:err_bad_request(<<"expected one history or statistics element">>, Lang)).

%%% --- a device's statistics ----------------------------------------------------------------------------------------
%% <statistics xmlns='urn:sabot:archive:1' device='BARE JID' [seconds='1..604800']/>: over the last SECONDS (default
%% 900) what ./sabot stats says of the device (docs/STATISTICS.md), as attributes, with one <error condition count/>
%% per ControlML condition and one <node name count/> per cluster node; sessions: the device's sessions now.
statistics(IQ, Host, El, Lang) ->
    case statistics_query(El) of
        {error, Text} ->
            xmpp:make_error(IQ, xmpp:err_bad_request(Text, Lang));
        {ok, Device, Seconds, Where} ->
            flush_cluster(Host),
            Counts = ejabberd_sql:sql_query(Host, [<<"SELECT count(*) FILTER (WHERE kind IN ('get', 'set'))::text, "
                "count(*) FILTER (WHERE kind = 'get')::text, count(*) FILTER (WHERE kind = 'set')::text, "
                "count(*) FILTER (WHERE kind = 'set' AND via = 'message')::text, "
                "count(*) FILTER (WHERE kind IN ('result', 'error'))::text, count(*) FILTER (WHERE kind = 'result')::text, "
                "count(*) FILTER (WHERE kind = 'error')::text, count(*) FILTER (WHERE kind = 'telemetry')::text, "
                "count(*)::text, "
                "(SELECT count(*)::text FROM sabot_requests q ">>, Where, <<" AND q.answer_ms IS NOT NULL), "
                "(SELECT coalesce(round(percentile_cont(0.5) WITHIN GROUP (ORDER BY q.answer_ms)::numeric, 1)::text, '') "
                "FROM sabot_requests q ">>, Where, <<" AND q.answer_ms IS NOT NULL), "
                "(SELECT coalesce(round(percentile_cont(0.99) WITHIN GROUP (ORDER BY q.answer_ms)::numeric, 1)::text, '') "
                "FROM sabot_requests q ">>, Where, <<" AND q.answer_ms IS NOT NULL), "
                "(SELECT coalesce(round(extract(epoch FROM now() - max(t.at))::numeric, 1)::text, '') FROM sabot_archive t "
                "WHERE t.device = ">>, literal(Device), <<" AND t.kind = 'telemetry') "
                "FROM sabot_archive q ">>, Where]),
            Errors = ejabberd_sql:sql_query(Host, [<<"SELECT coalesce(NULLIF(condition, ''), 'unspecified'), count(*)::text "
                "FROM sabot_archive q ">>, Where, <<" AND kind = 'error' GROUP BY 1 ORDER BY 1">>]),
            Nodes = ejabberd_sql:sql_query(Host, [<<"SELECT node, count(*)::text FROM sabot_archive q ">>, Where,
                                                  <<" GROUP BY 1 ORDER BY 1">>]),
            case {Counts, Errors, Nodes} of
                {{selected, _, [Row]}, {selected, _, ErrorRows}, {selected, _, NodeRows}} ->
                    {User, Server, _} = jid:tolower(jid:decode(Device)),
                    Sessions = length(ejabberd_sm:get_user_resources(User, Server)),
                    Names = [<<"requests">>, <<"gets">>, <<"sets">>, <<"stored">>, <<"answers">>, <<"results">>,
                             <<"errors">>, <<"telemetry">>, <<"stanzas">>, <<"answered">>, <<"p50">>, <<"p99">>,
                             <<"age">>],
                    Attrs = [{<<"xmlns">>, ?NS_ARCHIVE}, {<<"device">>, Device},
                             {<<"seconds">>, integer_to_binary(Seconds)},
                             {<<"sessions">>, integer_to_binary(Sessions)}]
                        ++ [{K, V} || {K, V} <- lists:zip(Names, Row), is_binary(V), V /= <<>>],
                    xmpp:make_iq_result(IQ, #xmlel{name = <<"statistics">>, attrs = Attrs,
                        children = [#xmlel{name = <<"error">>, attrs = [{<<"condition">>, C}, {<<"count">>, N}]}
                                    || [C, N] <- ErrorRows]
                                   ++ [#xmlel{name = <<"node">>, attrs = [{<<"name">>, C}, {<<"count">>, N}]}
                                       || [C, N] <- NodeRows]});
                Error ->
                    ?ERROR_MSG("Sabot archive: the statistics of ~ts not read: ~p", [Device, Error]),
                    xmpp:make_error(IQ, xmpp:err_internal_server_error(<<"the archive could not be read">>, Lang))
            end
    end.

statistics_query(El) ->
    Device = try jid:decode(attr(<<"device">>, El)) of
                 #jid{luser = U, lresource = <<>>} = J when U /= <<>> -> {ok, jid:encode(J)};
                 _ -> error
             catch _:_ -> error
             end,
    Seconds = int_attr(<<"seconds">>, El, ?STATISTICS_DEFAULT_S),
    case {Device, Seconds} of
        {error, _} -> {error, <<"device: expected a bare JID (robot@sabot.local)">>};
        {_, S} when not is_integer(S); S < 1; S > ?STATISTICS_MAX_S ->
            {error, iolist_to_binary(io_lib:format("seconds: expected 1..~B", [?STATISTICS_MAX_S]))};
        {{ok, D}, S} ->
            {ok, D, S, [<<"WHERE q.device = ">>, literal(D), <<" AND q.at >= now() - interval '1 second' * ">>,
                        integer_to_binary(S)]}
    end.

%% Every node's archiver writes what it holds: a history then has every command the cluster took before the request
%% (a node that does not answer within a second is left out, and logged).
flush_cluster(Host) ->
    Proc = gen_mod:get_module_proc(Host, ?MODULE),
    lists:foreach(fun(Node) ->
                          try gen_server:call({Proc, Node}, flush, 1000)
                          catch Class:Reason ->
                                  ?WARNING_MSG("Sabot archive: node ~p did not write what it holds (~p:~p)",
                                               [Node, Class, Reason])
                          end
                  end, ejabberd_cluster:get_nodes()).

-define(HISTORY_COLUMNS, [<<"seq">>, <<"at">>, <<"via">>, <<"res">>, <<"id">>, <<"from">>, <<"answer">>,
                          <<"condition">>, <<"text">>, <<"ms">>]).

history_query(#xmlel{name = <<"history">>} = El) ->
    Device = try jid:decode(attr(<<"device">>, El)) of
                 #jid{luser = U, lresource = <<>>} = J when U /= <<>> -> {ok, jid:encode(J)};
                 _ -> error
             catch _:_ -> error
             end,
    Max = int_attr(<<"max">>, El, ?HISTORY_DEFAULT),
    Before = int_attr(<<"before">>, El, none),
    case {Device, Max, Before} of
        {error, _, _} -> {error, <<"device: expected a bare JID (robot@sabot.local)">>};
        {_, M, _} when not is_integer(M); M < 1; M > ?HISTORY_MAX ->
            {error, iolist_to_binary(io_lib:format("max: expected 1..~B commands", [?HISTORY_MAX]))};
        {_, _, bad} -> {error, <<"before: expected a command's seq">>};
        {{ok, D}, _, _} ->
            {ok, D, [<<"SELECT seq, to_char(at AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS.MS\"Z\"'), via, res, "
                       "cm_id, sender, coalesce(answer, ''), condition, text, coalesce(answer_ms::text, '') "
                       "FROM sabot_commands WHERE device = ">>, literal(D),
                     case Before of
                         none -> <<>>;
                         _ -> [<<" AND (at, seq) < (SELECT at, seq FROM sabot_archive WHERE seq = ">>,
                               integer_to_binary(Before), <<")">>]
                     end,
                     <<" ORDER BY at DESC, seq DESC LIMIT ">>, integer_to_binary(Max)]}
    end;
history_query(_) ->
    {error, <<"expected <history xmlns='urn:sabot:archive:1' device='...'/>">>}.

int_attr(Name, El, Default) ->
    case attr(Name, El) of
        <<>> -> Default;
        V -> try binary_to_integer(V) of N when N >= 0 -> N; _ -> bad catch _:_ -> bad end
    end.

command(Row) ->
    #xmlel{name = <<"command">>,
           attrs = [{K, V} || {K, V} <- lists:zip(?HISTORY_COLUMNS, Row), is_binary(V), V /= <<>>]}.

%%% --- the archiver -------------------------------------------------------------------------------------------------
init([Host, Opts]) ->
    process_flag(trap_exit, true),
    ejabberd_hooks:add(user_send_packet, Host, ?MODULE, user_send_packet, 100),
    gen_iq_handler:add_iq_handler(ejabberd_local, Host, ?NS_ARCHIVE, ?MODULE, process_iq),
    erlang:send_after(0, self(), purge),
    ?INFO_MSG("Sabot archive of ControlML stanzas on ~ts: retention ~B days",
              [Host, gen_mod:get_opt(retention_days, Opts)]),
    {ok, #state{host = Host}}.

handle_call(flush, _From, State) ->
    {reply, ok, flush(State)};
handle_call(_Request, _From, State) ->
    {reply, {error, badarg}, State}.

handle_cast({row, Row}, #state{rows = Rows, held = Held} = State) ->
    State1 = State#state{rows = [Row | Rows], held = Held + 1},
    case Held + 1 >= ?BATCH of
        true -> {noreply, flush(State1)};
        false -> {noreply, arm(State1)}
    end;
handle_cast(_Msg, State) ->
    {noreply, State}.

handle_info(flush, State) ->
    {noreply, flush(State#state{timer = undefined})};
handle_info(purge, #state{host = Host} = State) ->
    Days = gen_mod:get_module_opt(Host, ?MODULE, retention_days),
    case ejabberd_sql:sql_query(Host, [<<"DELETE FROM sabot_archive WHERE at < now() - interval '">>,
                                       integer_to_binary(Days), <<" days'">>]) of
        {updated, N} when N > 0 -> ?INFO_MSG("Sabot archive: ~B rows older than ~B days deleted", [N, Days]);
        {updated, _} -> ok;
        Error -> ?ERROR_MSG("Sabot archive: the retention's delete failed: ~p", [Error])
    end,
    erlang:send_after(?PURGE_MS, self(), purge),
    {noreply, State};
handle_info(_Info, State) ->
    {noreply, State}.

terminate(_Reason, #state{host = Host} = State) ->
    ejabberd_hooks:delete(user_send_packet, Host, ?MODULE, user_send_packet, 100),
    gen_iq_handler:remove_iq_handler(ejabberd_local, Host, ?NS_ARCHIVE),
    flush(State),
    ok.

code_change(_OldVsn, State, _Extra) ->
    {ok, State}.

arm(#state{timer = undefined} = State) ->
    State#state{timer = erlang:send_after(?FLUSH_MS, self(), flush)};
arm(State) ->
    State.

flush(#state{held = 0} = State) ->
    State;
flush(#state{host = Host, rows = Rows, held = Held, dropped = Dropped, failing = Failing} = State) ->
    case ejabberd_sql:sql_query(Host, insert(Host, lists:reverse(Rows))) of
        {updated, Held} ->
            Failing andalso ?INFO_MSG("Sabot archive: writing again, ~B rows written (~B dropped meanwhile)",
                                      [Held, Dropped]),
            State#state{rows = [], held = 0, dropped = 0, failing = false};
        Error ->
            Failing orelse ?ERROR_MSG("Sabot archive: ~B rows not written, kept for the next attempt: ~p",
                                      [Held, Error]),
            {Kept, Lost} = case Held > ?MAX_HELD of
                               true -> {lists:sublist(Rows, ?MAX_HELD), Held - ?MAX_HELD};
                               false -> {Rows, 0}
                           end,
            Lost > 0 andalso ?ERROR_MSG("Sabot archive: ~B oldest rows dropped (more than ~B held)",
                                        [Lost, ?MAX_HELD]),
            arm(State#state{rows = Kept, held = Held - Lost, dropped = Dropped + Lost, failing = true})
    end.

insert(Host, Rows) ->
    Values = lists:join(<<",">>, [values(Host, Row) || Row <- Rows]),
    [<<"INSERT INTO sabot_archive (at, server_host, node, kind, via, res, cm_id, stanza_id, device, sender, "
       "recipient, condition, text, xml) VALUES ">>, Values].

values(Host, {At, Kind, Via, Res, CmId, StanzaId, Device, Sender, Recipient, Condition, Text, Xml}) ->
    Literals = [literal(V) || V <- [Host, atom_to_binary(node(), utf8), Kind, Via, Res, CmId, StanzaId, Device, Sender,
                                    Recipient, Condition, Text, Xml]],
    [<<"(to_timestamp(">>, integer_to_binary(At div 1000000), <<".">>,
     iolist_to_binary(io_lib:format("~6..0B", [At rem 1000000])), <<"),">>, lists:join(<<",">>, Literals), <<")">>].

literal(undefined) -> <<"''">>;
literal(Value) -> ejabberd_sql:to_string_literal(pgsql, Value).
