// Sabot Onboard portal: the status page asks /api/status every data-poll ms (no page reloads) and moves the robot on
// the map. Nothing else: forms are plain HTML forms.
(function () {
  'use strict';
  var poll = parseInt(document.body.getAttribute('data-poll'), 10);
  if (!poll || !document.getElementById('pose')) {
    return;
  }
  function text(id, value) {
    var e = document.getElementById(id);
    if (e) { e.textContent = value; }
  }
  function fixed(n, d) { return Number(n).toFixed(d); }
  function deg(rad) { return rad * 180 / Math.PI; }
  function show(s) {
    text('robot-name', s.robot);
    text('robot-jid', s.jid);
    text('robot-uuid', s.uuid);
    text('robot-page', s.page);
    text('online', s.online ? 'online' : 'offline');
    text('presence', s.presence.level + (s.presence.reason ? ' — ' + s.presence.reason : ''));
    var robot = document.getElementById('robot');
    if (s.pose) {
      text('pose', 'x ' + fixed(s.pose.x, 3) + ' m, y ' + fixed(s.pose.y, 3) + ' m, θ ' + fixed(deg(s.pose.theta), 1) + '°');
      text('velocity', fixed(s.velocity.linear, 3) + ' m/s, ' + fixed(s.velocity.angular, 3) + ' rad/s');
      text('mission', s.mission.state + (s.mission.maintenance ? ' (maintenance)' : '') + ', ' +
        Math.round(s.mission.progress) + ' %' + (s.mission.detail ? ' — ' + s.mission.detail : ''));
      text('targets', !s.mission.targets.length ? 'one goal' : s.mission.targets.map(function (t, i) {
        return (i + 1) + ' ' + t.action + ' (' + fixed(t.x, 2) + ', ' + fixed(t.y, 2) + ') ' + t.state;
      }).join(' · '));
      var b = s.battery;
      text('battery', !b ? 'not measured' : b.fault ? 'fault: ' + b.fault :
        fixed(b.stateOfCharge * 100, 0) + ' %, ' + fixed(b.voltage, 2) + ' V, ' + fixed(b.current, 2) + ' A' +
        (b.charging ? ', charging' : b.full ? ', full' : b.docked ? ', docked' : ''));
      if (robot) {
        robot.setAttribute('transform', 'translate(' + s.pose.x + ' ' + (-s.pose.y) + ') rotate(' + (-deg(s.pose.theta)) + ')');
        robot.setAttribute('visibility', 'visible');
        robot.setAttribute('data-x', s.pose.x);
        robot.setAttribute('data-y', s.pose.y);
      }
      var goal = document.getElementById('goal');
      if (s.goal && goal) {
        goal.setAttribute('cx', s.goal.x);
        goal.setAttribute('cy', -s.goal.y);
        goal.setAttribute('visibility', 'visible');
        text('goal', 'x ' + fixed(s.goal.x, 3) + ' m, y ' + fixed(s.goal.y, 3) + ' m');
      } else {
        text('goal', 'none');
      }
      var path = document.getElementById('path');
      if (path) {
        path.setAttribute('points', (s.path || []).map(function (p) { return p[0] + ',' + (-p[1]); }).join(' '));
      }
    } else {
      text('pose', 'no motion task');
      text('mission', 'no motion task');
      text('targets', 'no motion task');
      text('battery', 'no motion task');
    }
    text('updated', s.time);
    var rows = document.getElementById('task-rows');
    if (rows) {
      rows.textContent = '';
      s.tasks.forEach(function (t) {
        var tr = document.createElement('tr');
        var name = document.createElement('td');
        name.textContent = t.name;
        var state = document.createElement('td');
        state.textContent = t.status;
        tr.appendChild(name);
        tr.appendChild(state);
        rows.appendChild(tr);
      });
    }
    text('log-lines', s.log.join('\n'));
  }
  function tick() {
    var req = new XMLHttpRequest();
    req.open('GET', '/api/status');
    req.timeout = Math.max(2000, poll * 4);
    req.onload = function () {
      if (req.status === 401 || req.status === 403) {
        window.location.assign('/login');
        return;
      }
      if (req.status === 200) {
        document.getElementById('stale').hidden = true;
        show(JSON.parse(req.responseText));
      } else {
        document.getElementById('stale').hidden = false;
      }
      setTimeout(tick, poll);
    };
    req.onerror = req.ontimeout = function () {
      document.getElementById('stale').hidden = false;
      setTimeout(tick, poll);
    };
    req.send();
  }
  tick();
}());
