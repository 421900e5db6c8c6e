using System.Diagnostics;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Tests.BadInput;

/// <summary>
/// Bad command lines, each with the exit code (always 2, bad input) and a fragment its one-line error must hold. Paths
/// are tokens (@qr, @fifo, @profile:watchdog-0, ...) that <see cref="BadInputFiles"/> turns into real files.
/// </summary>
public static class BadInputTable
{
    /// <summary>Machine profiles with one bad field each, by token name; every one must be refused naming the field.</summary>
    public static readonly IReadOnlyDictionary<string, (string Json, string Fragment)> Profiles = new Dictionary<string, (string, string)>
    {
        ["gate-null"] = ("""{ "gate": null }""", "gate must not be null"),
        ["x-null"] = ("""{ "x": null }""", "x must not be null"),
        ["y-null"] = ("""{ "y": null }""", "y must not be null"),
        ["name-null"] = ("""{ "name": null }""", "name must not be empty"),
        ["watchdog-0"] = ("""{ "gate": { "watchdogMs": 0 } }""", "gate.watchdogMs must be 50..60000 ms"),
        ["watchdog-49"] = ("""{ "gate": { "watchdogMs": 49 } }""", "gate.watchdogMs must be 50..60000 ms"),
        ["watchdog-huge"] = ("""{ "gate": { "watchdogMs": 600000 } }""", "gate.watchdogMs must be 50..60000 ms"),
        ["watchdog-text"] = ("""{ "gate": { "watchdogMs": "soon" } }""", "gate.watchdogMs has a value of the wrong type"),
        ["off-ping"] = ("""{ "gate": { "offCommand": "PING" } }""", "is the same as gate.offCommand \"PING\""),
        ["keepalive-off"] = ("""{ "gate": { "keepAliveCommand": "OFF" } }""", "gate.keepAliveCommand \"OFF\" is the same as gate.offCommand"),
        ["off-freq-0"] = ("""{ "gate": { "offCommand": "FREQ 0" } }""", "gate.offCommand \"FREQ 0\" begins like gate.frequencyCommand"),
        ["status-prefix"] = ("""{ "gate": { "statusCommand": "OF" } }""", "gate.statusCommand \"OF\" begins like gate.offCommand"),
        ["off-empty"] = ("""{ "gate": { "offCommand": "" } }""", "gate.offCommand must not be empty"),
        ["identify-null"] = ("""{ "gate": { "identifyCommand": null } }""", "gate.identifyCommand must not be empty"),
        ["freq-no-value"] = ("""{ "gate": { "frequencyCommand": "FREQ" } }""", "must hold {0}"),
        ["freq-bad-template"] = ("""{ "gate": { "frequencyCommand": "FREQ {1}" } }""", "is not a valid template"),
        ["burst-one-value"] = ("""{ "gate": { "burstCommand": "BURST {0}" } }""", "gate.burstCommand \"BURST {0}\" must hold {1}"),
        ["wdog-value-first"] = ("""{ "gate": { "watchdogCommand": "{0} WDOG" } }""", "must begin with a command word"),
        ["off-two-lines"] = ("""{ "gate": { "offCommand": "OFF\nNOW" } }""", "gate.offCommand must be one line"),
        ["ack-empty"] = ("""{ "gate": { "ackPrefix": "" } }""", "gate.ackPrefix must not be empty"),
        ["error-is-ack"] = ("""{ "gate": { "errorPrefix": "OK" } }""", "gate.errorPrefix \"OK\" and gate.ackPrefix \"OK\" must differ"),
        ["terminator"] = ("""{ "gate": { "lineTerminator": ";" } }""", "gate.lineTerminator must be"),
        ["timeout-0"] = ("""{ "gate": { "timeoutMs": 0 } }""", "gate.timeoutMs must be 1..60000 ms"),
        ["gate-baud"] = ("""{ "gate": { "baudRate": 12345 } }""", "gate.baudRate must be one of"),
        ["scan-speed-0"] = ("""{ "scanOffsets": [ { "speedMmPerS": 0, "offsetUm": 1 } ] }""", "scanOffsets[0].speedMmPerS must be a finite speed above 0"),
        ["scan-unsorted"] = ("""{ "scanOffsets": [ { "speedMmPerS": 2, "offsetUm": 1 }, { "speedMmPerS": 1, "offsetUm": 1 } ] }""", "scanOffsets[1].speedMmPerS must be above"),
        ["scan-too-far"] = ("""{ "scanOffsets": [ { "speedMmPerS": 1, "offsetUm": 2000 } ] }""", "scanOffsets[0].offsetUm must be finite and at most 1000 µm"),
        ["gate-max-frequency"] = ("""{ "gate": { "maxFrequencyHz": 200000 } }""", "gate.maxFrequencyHz must be 1..100000 Hz"),
        ["frequency-huge"] = ("""{ "laserFrequencyHz": 1e12 }""", "laserFrequencyHz must be 1..100000 Hz"),
        ["frequency-above-gate"] = ("""{ "gate": { "maxFrequencyHz": 500 } }""", "laserFrequencyHz must be 1..500 Hz"),
        ["frame-frequency-0"] = ("""{ "maxFrameFrequencyHz": 0 }""", "maxFrameFrequencyHz must be 1..100000 Hz"),
        ["burn-speed"] = ("""{ "burnSpeedMmPerS": 5 }""", "burnSpeedMmPerS must be 0.00093..4 mm/s"),
        ["travel-speed"] = ("""{ "travelSpeedMmPerS": 0 }""", "travelSpeedMmPerS must be 0.00093..4 mm/s"),
        ["acceleration"] = ("""{ "accelerationMmPerS2": 500 }""", "accelerationMmPerS2 must be 1.11621..200 mm/s²"),
        ["x-max-speed"] = ("""{ "x": { "deviceNumber": 1, "maxSpeedMmPerS": 40 } }""", "x.maxSpeedMmPerS must be 0.00093..30.47907 mm/s"),
        ["y-max-acceleration"] = ("""{ "y": { "deviceNumber": 2, "maxAccelerationMmPerS2": 0 } }""", "y.maxAccelerationMmPerS2 must be"),
        ["travel-huge"] = ("""{ "x": { "deviceNumber": 1, "travelMm": 2000 } }""", "x.travelMm must be above 0 and at most 1664.6143 mm"),
        ["travel-0"] = ("""{ "y": { "deviceNumber": 2, "travelMm": 0 } }""", "y.travelMm must be above 0"),
        ["device-0"] = ("""{ "x": { "deviceNumber": 0 } }""", "x.deviceNumber must be 1..254"),
        ["same-device"] = ("""{ "y": { "deviceNumber": 1 } }""", "x.deviceNumber and y.deviceNumber cannot both be 1"),
        ["microstep-0"] = ("""{ "x": { "deviceNumber": 1, "microstepUm": 0 } }""", "x.microstepUm must be above 0"),
        ["stage-baud"] = ("""{ "stageBaudRate": 115200 }""", "stageBaudRate must be 9600"),
        ["spot"] = ("""{ "spotDiameterUm": -1 }""", "spotDiameterUm must be a finite number above 0"),
        ["z-same-device"] = ("""{ "z": { "deviceNumber": 2 } }""", "z.deviceNumber and y.deviceNumber cannot both be 2"),
        ["z-focus-outside"] = ("""{ "z": { "focusMm": 30 } }""", "z.focusMm must be within z.minMm..z.maxMm 0..25 mm (got 30)"),
        ["z-speed"] = ("""{ "z": { "speedMmPerS": 5 } }""", "z.speedMmPerS must be 0.00093..2 mm/s"),
        ["z-limits"] = ("""{ "z": { "minMm": 10, "maxMm": 5 } }""", "z.maxMm must be above z.minMm 10 mm"),
        ["z-misspelt"] = ("""{ "z": { "focusUm": 5 } }""", "z.focusUm is not a field of the machine profile"),
        ["unknown-field"] = ("""{ "gate": { "WatchdogMs": 0 } }""", "gate.WatchdogMs is not a field of the machine profile"),
        ["off-reply-null"] = ("""{ "gate": { "offReply": null } }""", "gate.offReply must not be null"),
        ["burst-reply-null"] = ("""{ "gate": { "burstReply": null } }""", "gate.burstReply must not be null"),
        ["watchdog-reply-5"] = ("""{ "gate": { "watchdogReply": "FREQ {5}" } }""", "gate.watchdogReply \"FREQ {5}\" is not a valid reply template"),
        ["frequency-reply-1"] = ("""{ "gate": { "frequencyReply": "FREQ {1}" } }""", "gate.frequencyReply \"FREQ {1}\" is not a valid reply template"),
        ["burst-reply-brace"] = ("""{ "gate": { "burstReply": "BURST {0" } }""", "gate.burstReply \"BURST {0\" is not a valid reply template"),
        ["status-reply-empty"] = ("""{ "gate": { "statusReply": "" } }""", "gate.statusReply must not be empty"),
        ["keepalive-reply-two-lines"] = ("""{ "gate": { "keepAliveReply": "PONG\nPONG" } }""", "gate.keepAliveReply must be one line"),
        ["terminator-null"] = ("""{ "gate": { "lineTerminator": null } }""", "gate.lineTerminator must be \"\\n\", \"\\r\\n\" or \"\\r\" (got null)"),
        ["terminator-two"] = ("""{ "gate": { "lineTerminator": "\n\n" } }""", "gate.lineTerminator must be"),
        ["latency-null"] = ("""{ "latency": null }""", "latency must not be null"),
        ["travel-1e308"] = ("""{ "x": { "deviceNumber": 1, "travelMm": 1e308 } }""", "x.travelMm must be above 0 and at most"),
        ["frequency-1e400"] = ("""{ "laserFrequencyHz": 1e400 }""", "laserFrequencyHz"),
        ["frequency-text-nan"] = ("""{ "laserFrequencyHz": "NaN" }""", "laserFrequencyHz has a value of the wrong type"),
        ["device-fraction"] = ("""{ "x": { "deviceNumber": 1.5 } }""", "x.deviceNumber has a value of the wrong type"),
        // Issue 35: once refused only by the planners, when the first job was planned (and never by jog, goto or fire).
        ["microsteps-unequal"] = ("""{ "y": { "deviceNumber": 2, "microstepUm": 0.2 } }""", "x.microstepUm 0.09921875 and y.microstepUm 0.2 must be equal"),
        ["microstep-negative"] = ("""{ "y": { "deviceNumber": 2, "microstepUm": -0.1 } }""", "y.microstepUm must be above 0"),
        ["spot-negative-zero"] = ("""{ "spotDiameterUm": -0.0 }""", "spotDiameterUm must be a finite number above 0"),
        ["array"] = ("""[1, 2]""", "not a valid machine profile"),
        ["json-null"] = ("""null""", "the machine profile is empty"),
        ["empty"] = ("", "not valid JSON at line 1, column 1: the file is empty"),
        ["not-json"] = ("watchdog = 0", "not valid JSON at line 1, column 1: 'w' cannot begin a value"),
    };

    /// <summary>The bad command lines: args, exit code, a fragment of the one-line error.</summary>
    public static TheoryData<string[], int, string> All()
    {
        var rows = new TheoryData<string[], int, string>();
        void Add(string fragment, params string[] args) => rows.Add(args, 2, fragment);

        // Files that are not images, or not regular files: none may block, each is refused naming the file.
        foreach (var command in new[] { "info", "mask" })
        {
            var tail = command == "mask" ? new[] { "--out", "@out" } : [];
            Add("named pipe (FIFO)", [command, "@fifo", .. tail]);
            Add("is a folder", [command, "@dir", .. tail]);
            Add("is a character device", [command, "@dev", .. tail]);
            Add("file not found", [command, "@missing", .. tail]);
            Add("@empty:", [command, "@empty", .. tail]);
            Add("@text:", [command, "@text", .. tail]);
            Add("the file is truncated", [command, "@truncated", .. tail]);
        }

        Add("Required argument missing", "info");
        Add("--threshold 101", "mask", "@qr", "--out", "@out", "--threshold", "101");
        Add("--threshold -1", "mask", "@qr", "--out", "@out", "--threshold", "-1");
        Add("--threshold NaN", "mask", "@qr", "--out", "@out", "--threshold", "NaN");
        Add("--threshold Infinity", "mask", "@qr", "--out", "@out", "--threshold", "Infinity");
        Add("abc", "mask", "@qr", "--out", "@out", "--threshold", "abc");
        Add("--dither zigzag", "mask", "@qr", "--out", "@out", "--dither", "zigzag");
        Add("--out", "mask", "@qr");

        // Every number of a job, on plan (which only computes) and on the commands that move.
        var job = new (string Fragment, string[] Options)[]
        {
            ("--width-mm 0: must be a finite number above 0", ["--width-mm", "0"]),
            ("--width-mm -5: must be a finite number above 0", ["--width-mm", "-5"]),
            ("--width-mm NaN: is not a number", ["--width-mm", "NaN"]),
            ("--width-mm Infinity: is not a number", ["--width-mm", "Infinity"]),
            ("--width-mm -Infinity: is not a number", ["--width-mm", "-Infinity"]),
            ("--width-mm 1E+300: at most 60 mm, the X travel", ["--width-mm", "1e300"]),
            ("--width-mm 100: at most 60 mm, the X travel", ["--width-mm", "100"]),
            ("--width-mm 1E-300 for 41 x 41 px gives pixels of", ["--width-mm", "1e-300"]),
            ("--width-mm 0.0001 for 41 x 41 px gives pixels of 0.00244 µm, below one microstep", ["--width-mm", "0.0001"]),
            ("--width-mm abc: is not a number", ["--width-mm", "abc"]),
            ("--height-mm 0: must be a finite number above 0", ["--height-mm", "0"]),
            ("--height-mm NaN", ["--height-mm", "NaN"]),
            ("--height-mm 1E+300: at most 60 mm, the Y travel", ["--height-mm", "1e300"]),
            ("--height-mm 1E-300 for 41 x 41 px gives pixels of", ["--height-mm", "1e-300"]),
            ("--pitch-um 0: must be a finite number above 0", ["--pitch-um", "0"]),
            ("--pitch-um 0.01: below one microstep", ["--pitch-um", "0.01"]),
            ("--pitch-um 1E+300: at most 60000 µm, the travel", ["--pitch-um", "1e300"]),
            ("--pitch-um NaN", ["--pitch-um", "NaN"]),
            ("one way only", ["--width-mm", "5", "--pitch-um", "40"]),
            ("give the size", []),
            ("--origin-mm 10: expected two numbers", ["--width-mm", "1", "--origin-mm", "10"]),
            ("--origin-mm: X -1 mm is outside the travel 0..60 mm", ["--width-mm", "1", "--origin-mm", "-1,0"]),
            ("--origin-mm: Y -1 mm is outside the travel 0..60 mm", ["--width-mm", "1", "--origin-mm", "0,-1"]),
            ("--origin-mm: X 61 mm is outside the travel", ["--width-mm", "1", "--origin-mm", "61,0"]),
            ("--origin-mm: X 1E+300 mm is outside the travel", ["--width-mm", "1", "--origin-mm", "1e300,0"]),
            ("--origin-mm NaN,0: X 'NaN' is not a number", ["--width-mm", "1", "--origin-mm", "NaN,0"]),
            ("--origin-mm a,b: X 'a' is not a number", ["--width-mm", "1", "--origin-mm", "a,b"]),
            ("--origin-mm 1,2,3: could be read more than one way", ["--width-mm", "1", "--origin-mm", "1,2,3"]),
            ("--overscan-mm -1: must be 0..60 mm", ["--width-mm", "1", "--overscan-mm", "-1"]),
            ("--overscan-mm NaN: is not a number", ["--width-mm", "1", "--overscan-mm", "NaN"]),
            ("--overscan-mm 1E+300: must be 0..60 mm", ["--width-mm", "1", "--overscan-mm", "1e300"]),
            ("--overscan-mm Infinity: is not a number", ["--width-mm", "1", "--overscan-mm", "Infinity"]),
            ("--strategy zigzag", ["--width-mm", "1", "--strategy", "zigzag"]),
            ("--mode spots: use raster or dots", ["--width-mm", "1", "--mode", "spots"]),
            ("--pulses-per-dot applies to --mode dots only", ["--width-mm", "1", "--pulses-per-dot", "5"]),
            ("--dot-pitch-microsteps applies to --mode dots only", ["--width-mm", "1", "--mode", "raster", "--dot-pitch-microsteps", "100"]),
            ("--pulses-per-dot 0: must be 1..1000000", ["--width-mm", "1", "--mode", "dots", "--pulses-per-dot", "0"]),
            ("--pulses-per-dot -3: must be 1..1000000", ["--width-mm", "1", "--mode", "dots", "--pulses-per-dot", "-3"]),
            ("--dot-pitch-microsteps -1: must be 0 (one dot at each pixel's centre) to", ["--width-mm", "1", "--mode", "dots", "--dot-pitch-microsteps", "-1"]),
            ("--dot-settle-ms NaN: is not a number", ["--width-mm", "1", "--mode", "dots", "--dot-settle-ms", "NaN"]),
            ("--dot-settle-ms -1: must be 0..60000 ms", ["--width-mm", "1", "--mode", "dots", "--dot-settle-ms", "-1"]),
            ("contradict each other", ["--width-mm", "1", "--bidirectional", "--unidirectional"]),
            ("--speed-mm-s 100: outside what the stage takes, 0.00093..4 mm/s", ["--width-mm", "1", "--speed-mm-s", "100"]),
            ("--speed-mm-s 0: outside what the stage takes", ["--width-mm", "1", "--speed-mm-s", "0"]),
            ("--speed-mm-s -1: outside what the stage takes", ["--width-mm", "1", "--speed-mm-s", "-1"]),
            ("--speed-mm-s NaN: is not a number", ["--width-mm", "1", "--speed-mm-s", "NaN"]),
            ("--speed-mm-s 1E-09: outside what the stage takes", ["--width-mm", "1", "--speed-mm-s", "1e-9"]),
            ("--speed-mm-s Infinity: is not a number", ["--width-mm", "1", "--speed-mm-s", "Infinity"]),
            ("--travel-speed-mm-s 100: outside what the stage takes", ["--width-mm", "1", "--travel-speed-mm-s", "100"]),
            ("--travel-speed-mm-s 0: outside what the stage takes", ["--width-mm", "1", "--travel-speed-mm-s", "0"]),
            ("--travel-speed-mm-s NaN: is not a number", ["--width-mm", "1", "--travel-speed-mm-s", "NaN"]),
            ("--acceleration-mm-s2 1000000: outside what the stage takes, 1.11621..200 mm/s²", ["--width-mm", "1", "--acceleration-mm-s2", "1e6"]),
            ("--acceleration-mm-s2 0: outside", ["--width-mm", "1", "--acceleration-mm-s2", "0"]),
            ("--acceleration-mm-s2 -5: outside", ["--width-mm", "1", "--acceleration-mm-s2", "-5"]),
            ("--acceleration-mm-s2 0.5: outside", ["--width-mm", "1", "--acceleration-mm-s2", "0.5"]),
            ("--frequency-hz 1E+12: outside what the laser gate takes, 1..100000 Hz", ["--width-mm", "1", "--frequency-hz", "1e12"]),
            ("--frequency-hz 0: outside what the laser gate takes", ["--width-mm", "1", "--frequency-hz", "0"]),
            ("--frequency-hz -1000: outside", ["--width-mm", "1", "--frequency-hz", "-1000"]),
            ("--frequency-hz NaN: is not a number", ["--width-mm", "1", "--frequency-hz", "NaN"]),
            ("--frequency-hz 0.2: outside", ["--width-mm", "1", "--frequency-hz", "0.2"]),
            ("--frequency-hz 100001: outside", ["--width-mm", "1", "--frequency-hz", "100001"]),
            ("--threshold 200", ["--width-mm", "1", "--threshold", "200"]),
            ("--dither nope", ["--width-mm", "1", "--dither", "nope"]),
            ("@missing: cannot read the machine profile", ["--width-mm", "1", "--profile", "@missing"]),
            ("@fifo: is a named pipe (FIFO)", ["--width-mm", "1", "--profile", "@fifo"]),
            ("@dir: is a folder", ["--width-mm", "1", "--profile", "@dir"]),
        };
        foreach (var (fragment, options) in job)
        {
            Add(fragment, ["plan", "@qr", .. options]);
        }

        foreach (var (name, (_, fragment)) in Profiles)
        {
            Add(fragment, "plan", "@qr", "--width-mm", "1", "--profile", $"@profile:{name}");
        }

        // The commands that move: every refusal must come before the machine (here the simulator) is created.
        foreach (var index in new[] { 0, 2, 5, 7, 8, 13, 16, 21, 24, 30, 34, 38, 43, 47, 51, 56, 57 })
        {
            var (fragment, options) = job[index];
            Add(fragment, ["engrave", "@qr", .. options, "--simulate", "--log-dir", "@logdir"]);
        }

        foreach (var index in new[] { 7, 23, 34, 47 })
        {
            var (fragment, options) = job[index];
            Add(fragment, ["frame", "@qr", .. options, "--simulate"]);
        }

        foreach (var name in new[] { "watchdog-0", "off-ping", "gate-null", "keepalive-off", "frequency-huge" })
        {
            Add(Profiles[name].Fragment, "engrave", "@qr", "--width-mm", "1", "--simulate", "--log-dir", "@logdir", "--profile", $"@profile:{name}");
        }

        string[] engrave = ["engrave", "@qr", "--width-mm", "1", "--log-dir", "@logdir"];
        Add("does not fit the stage's travel", [.. engrave, "--origin-mm", "59.5,59.5", "--simulate"]);
        Add("give the machine: --simulate, or --stage-port P --laser-port Q", engrave);
        Add("--simulate and --stage-port/--laser-port contradict each other", [.. engrave, "--simulate", "--stage-port", "/dev/null"]);
        Add("give both ports: --laser-port is missing", [.. engrave, "--stage-port", "/nonexistent/tty"]);
        Add("--fault works only with --simulate", [.. engrave, "--stage-port", "/nonexistent/a", "--laser-port", "/nonexistent/b", "--fault", "silent:gate"]);
        Add("bogus", [.. engrave, "--simulate", "--fault", "bogus"]);
        Add("--burned needs --simulate", [.. engrave, "--stage-port", "/nonexistent/a", "--laser-port", "/nonexistent/b", "--burned", "@out"]);
        Add("--resume needs --from-log", [.. engrave, "--simulate", "--resume"]);
        Add("--passes 0: must be 1..100", [.. engrave, "--simulate", "--passes", "0"]);
        Add("--passes -3: must be 1..100", [.. engrave, "--simulate", "--passes", "-3"]);
        Add("--passes 101: must be 1..100", [.. engrave, "--simulate", "--passes", "101"]);
        Add("--passes", [.. engrave, "--simulate", "--passes", "two"]);
        Add("lasts 600 ms, more than half the gate's watchdog time (1000 ms)", [.. engrave, "--simulate", "--mode", "dots", "--pulses-per-dot", "600"]);
        Add("named pipe (FIFO)", "engrave", "@fifo", "--width-mm", "1", "--simulate", "--log-dir", "@logdir");
        Add("is a folder", "engrave", "@dir", "--width-mm", "1", "--simulate", "--log-dir", "@logdir");
        Add("the file is truncated", "engrave", "@truncated", "--width-mm", "1", "--simulate", "--log-dir", "@logdir");
        Add("file not found", "engrave", "@missing", "--width-mm", "1", "--simulate", "--log-dir", "@logdir");

        // A sweep's every value is checked before the machine opens.
        string[] sweep = ["sweep", "--simulate", "--log-dir", "@logdir"];
        Add("give what the rows vary: --rows", sweep);
        Add("--rows speed=1,10: speed 10 mm/s: outside what the stage takes", [.. sweep, "--rows", "speed=1,10"]);
        Add("--rows colour=1: 'colour' is not a sweep parameter", [.. sweep, "--rows", "colour=1"]);
        Add("--rows passes=1.5: passes takes whole numbers", [.. sweep, "--rows", "passes=1.5"]);
        Add("--columns frequency=0: frequency 0 Hz: outside what the laser gate takes", [.. sweep, "--rows", "speed=1", "--columns", "frequency=0"]);
        Add("add --mode dots", [.. sweep, "--rows", "pulses-per-dot=1,5"]);
        Add("--pattern stars: use square, lines, dots or image", [.. sweep, "--rows", "speed=1", "--pattern", "stars"]);
        Add("--pattern image needs the cell's image: --cell-image FILE", [.. sweep, "--rows", "speed=1", "--pattern", "image"]);
        Add("--cell-image goes with --pattern image", [.. sweep, "--rows", "speed=1", "--cell-image", "@qr"]);
        Add("@text: not a BMP, PNG", [.. sweep, "--rows", "speed=1", "--pattern", "image", "--cell-image", "@text"]);
        Add("@missing: file not found", [.. sweep, "--rows", "speed=1", "--pattern", "image", "--cell-image", "@missing"]);
        Add("@dir: is a folder", [.. sweep, "--rows", "speed=1", "--pattern", "image", "--cell-image", "@dir"]);
        Add("so its pitch cannot be swept", [.. sweep, "--rows", "pitch=20,40", "--pattern", "image", "--cell-image", "@qr"]);

        // The focus is swept only on a machine with a Z axis, and only within its limits; nothing opens before.
        Add("--rows focus=-100,0,100: focus -100 µm: the machine has no Z axis", [.. sweep, "--rows", "focus=-100,0,100"]);
        string[] focus = ["focus-series", "--simulate", "--log-dir", "@logdir"];
        Add("give the focus positions: --focus-um FROM..TO:STEP", focus);
        Add("--focus-um -100,-50,0,50,100: focus -100 µm: the machine has no Z axis", [.. focus, "--focus-um", "-100..100:50"]);
        Add("--focus-um 0,-13000: focus -13000 µm: puts Z at -0.5 mm, outside z.minMm..z.maxMm 5..20 mm", [.. focus, "--focus-um", "0,-13000", "--profile", "@zprofile"]);
        Add("--focus-um -100..100:0: the step must be above 0", [.. focus, "--focus-um", "-100..100:0", "--profile", "@zprofile"]);
        Add("--focus-um -100..100:2: 101 values, at most 50", [.. focus, "--focus-um", "-100..100:2", "--profile", "@zprofile"]);
        Add("--focus-um 1..2: expected FROM..TO:STEP", [.. focus, "--focus-um", "1..2", "--profile", "@zprofile"]);
        Add("--cell-mm 0: must be above 0", [.. sweep, "--rows", "speed=1", "--cell-mm", "0"]);
        Add("--pitch-um 0.01: must be", [.. sweep, "--rows", "speed=1", "--pitch-um", "0.01"]);
        Add("reaches past the stage travel", [.. sweep, "--rows", "speed=1,2", "--origin-mm", "59,59"]);
        Add("--speed-mm-s 100: outside what the stage takes", [.. sweep, "--rows", "frequency=500", "--speed-mm-s", "100"]);
        Add("--dose-dir needs --simulate", "sweep", "--rows", "speed=1", "--stage-port", "/nonexistent/a", "--laser-port", "/nonexistent/b", "--dose-dir", "@out");

        // A repeated run takes everything from its log: options it would ignore are refused, and so is a bad log.
        string[] fromLog = ["engrave", "--from-log", "@log", "--simulate", "--log-dir", "@logdir"];
        Add("--width-mm with --from-log", [.. fromLog, "--width-mm", "5"]);
        Add("--height-mm with --from-log", [.. fromLog, "--height-mm", "5"]);
        Add("--pitch-um with --from-log", [.. fromLog, "--pitch-um", "50"]);
        Add("--passes with --from-log", [.. fromLog, "--passes", "2"]);
        Add("--frequency-hz with --from-log", [.. fromLog, "--frequency-hz", "5000"]);
        Add("--speed-mm-s with --from-log", [.. fromLog, "--speed-mm-s", "2"]);
        Add("--origin-mm with --from-log", [.. fromLog, "--origin-mm", "5,5"]);
        Add("--threshold with --from-log", [.. fromLog, "--threshold", "40"]);
        Add("--invert with --from-log", [.. fromLog, "--invert"]);
        Add("--strategy with --from-log", [.. fromLog, "--strategy", "paper"]);
        Add("--mode with --from-log", [.. fromLog, "--mode", "dots"]);
        Add("--pulses-per-dot with --from-log", [.. fromLog, "--pulses-per-dot", "3"]);
        Add("--profile with --from-log", [.. fromLog, "--profile", "@profile:watchdog-0"]);
        Add("give IMAGE (", [.. fromLog, "@qr"]);
        Add("nothing to resume", [.. fromLog, "--resume"]);
        Add("no such run log", "engrave", "--from-log", "@missing", "--simulate", "--log-dir", "@logdir");
        Add("named pipe (FIFO)", "engrave", "--from-log", "@fifo", "--simulate", "--log-dir", "@logdir");
        Add("is a folder", "engrave", "--from-log", "@dir", "--simulate", "--log-dir", "@logdir");
        Add("@text", "engrave", "--from-log", "@text", "--simulate", "--log-dir", "@logdir");
        Add("gate.watchdogMs must be 50..60000 ms", "engrave", "--from-log", "@log-watchdog-0", "--simulate", "--log-dir", "@logdir");
        Add("@log-fast: process.burnSpeedMmPerS 100: outside what the stage takes, 0.00093..4 mm/s", "engrave", "--from-log", "@log-fast", "--simulate", "--log-dir", "@logdir");

        // frame: the laser is on around the whole frame at --visible-hz, so the profile caps it.
        string[] frame = ["frame", "@qr", "--width-mm", "1", "--simulate"];
        Add("--visible-hz 100000: must be 1..100 Hz (the profile's maxFrameFrequencyHz)", [.. frame, "--visible-hz", "100000"]);
        Add("--visible-hz 101: must be 1..100 Hz", [.. frame, "--visible-hz", "101"]);
        Add("--visible-hz 0: must be 1..100 Hz", [.. frame, "--visible-hz", "0"]);
        Add("--visible-hz -5: must be 1..100 Hz", [.. frame, "--visible-hz", "-5"]);
        Add("--visible-hz abc: is not a whole number", [.. frame, "--visible-hz", "abc"]);
        Add("--visible-hz 1e12: is not a whole number", [.. frame, "--visible-hz", "1e12"]);
        Add("gate.watchdogMs must be 50..60000 ms", [.. frame, "--profile", "@profile:watchdog-0"]);
        Add("does not fit the stage's travel", [.. frame, "--origin-mm", "59.5,59.5"]);
        Add("give the machine", "frame", "@qr", "--width-mm", "1");

        // jog, goto: targets off the axis, non-numbers, no machine.
        Add("STEP_UM 1E+12: longer than the X travel (60000 µm)", "jog", "x", "1e12", "--simulate");
        Add("STEP_UM -1E+300: longer than the X travel", "jog", "x", "-1e300", "--simulate");
        Add("STEP_UM 70000: longer than the Y travel (60000 µm)", "jog", "y", "70000", "--simulate");
        Add("STEP_UM NaN: is not a number", "jog", "x", "NaN", "--simulate");
        Add("STEP_UM Infinity: is not a number", "jog", "x", "Infinity", "--simulate");
        Add("STEP_UM 0: must be a finite number other than 0", "jog", "y", "0", "--simulate");
        Add("AXIS z: use x or y", "jog", "z", "100", "--simulate");
        Add("STEP_UM abc: is not a number", "jog", "x", "abc", "--simulate");
        Add("give the machine", "jog", "x", "100");
        Add("gate must not be null", "jog", "x", "100", "--simulate", "--profile", "@profile:gate-null");
        Add("x.microstepUm 0.09921875 and y.microstepUm 0.2 must be equal", "jog", "x", "100", "--simulate", "--profile", "@profile:microsteps-unequal");
        Add("X_MM 100: outside the travel 0..60 mm", "goto", "100", "0", "--simulate");
        Add("Y_MM 100: outside the travel 0..60 mm", "goto", "0", "100", "--simulate");
        Add("X_MM -1: outside the travel", "goto", "-1", "0", "--simulate");
        Add("X_MM NaN: is not a number", "goto", "NaN", "0", "--simulate");
        Add("Y_MM Infinity: is not a number", "goto", "0", "Infinity", "--simulate");
        Add("X_MM 1E+300: outside the travel", "goto", "1e300", "0", "--simulate");
        Add("X_MM a: is not a number", "goto", "a", "b", "--simulate");
        Add("give the machine", "goto", "1", "2");
        Add("gate.watchdogMs must be 50..60000 ms", "goto", "1", "2", "--simulate", "--profile", "@profile:watchdog-0");

        // fire: counts, durations and frequencies within the gate's range.
        Add("give one of --pulses N or --ms T", "fire", "--simulate");
        Add("give one of --pulses N or --ms T", "fire", "--pulses", "5", "--ms", "10", "--simulate");
        Add("--pulses 0: must be 1..1000000", "fire", "--pulses", "0", "--simulate");
        Add("--pulses -5: must be 1..1000000", "fire", "--pulses", "-5", "--simulate");
        Add("--pulses 2000000: must be 1..1000000 pulses (the laser gate's burst range)", "fire", "--pulses", "2000000", "--simulate");
        Add("--ms 0: must be 1..60000 ms", "fire", "--ms", "0", "--simulate");
        Add("--ms -1: must be 1..60000 ms", "fire", "--ms", "-1", "--simulate");
        Add("--ms 100000: must be 1..60000 ms", "fire", "--ms", "100000", "--simulate");
        Add("--frequency-hz 0: must be 1..100000 Hz", "fire", "--pulses", "5", "--frequency-hz", "0", "--simulate");
        Add("--frequency-hz -5: must be 1..100000 Hz", "fire", "--pulses", "5", "--frequency-hz", "-5", "--simulate");
        Add("--frequency-hz 200000: must be 1..100000 Hz", "fire", "--pulses", "5", "--frequency-hz", "200000", "--simulate");
        Add("--frequency-hz 1e12: is not a whole number", "fire", "--pulses", "5", "--frequency-hz", "1e12", "--simulate");
        Add("--pulses abc: is not a whole number", "fire", "--pulses", "abc", "--simulate");
        Add("is the same as gate.offCommand \"PING\"", "fire", "--pulses", "5", "--simulate", "--profile", "@profile:off-ping");
        Add("give the machine", "fire", "--pulses", "5");

        // The wiring checks: the numbers and the profile are refused before the port (which does not exist) is tried.
        Add("X 1E+300 µm is outside the travel 0..60000 µm", "stage", "--port", "/nonexistent/tty", "move-abs", "1e300", "0");
        Add("X -1 µm is outside the travel", "stage", "--port", "/nonexistent/tty", "move-abs", "-1", "0");
        Add("X_UM NaN: is not a number", "stage", "--port", "/nonexistent/tty", "move-abs", "NaN", "0");
        Add("Y 70000 µm is outside the travel", "stage", "--port", "/nonexistent/tty", "move-abs", "0", "70000");
        Add("X_UM abc: is not a number", "stage", "--port", "/nonexistent/tty", "move-abs", "abc", "0");
        Add("gate.watchdogMs must be 50..60000 ms", "stage", "--port", "/nonexistent/tty", "identify", "--profile", "@profile:watchdog-0");
        Add("--port", "stage", "identify");
        Add("HZ must be above 0 (got 0)", "laser", "--port", "/nonexistent/tty", "on", "0");
        Add("HZ must be above 0 (got -5)", "laser", "--port", "/nonexistent/tty", "on", "-5");
        Add("HZ 200000: must be 1..100000 Hz", "laser", "--port", "/nonexistent/tty", "on", "200000");
        Add("--seconds 0: must be above 0", "laser", "--port", "/nonexistent/tty", "on", "1000", "--seconds", "0");
        Add("--seconds NaN: is not a number", "laser", "--port", "/nonexistent/tty", "on", "1000", "--seconds", "NaN");
        Add("--seconds -1: must be above 0", "laser", "--port", "/nonexistent/tty", "on", "1000", "--seconds", "-1");
        Add("--seconds 1E+12: must be above 0 and at most 86400", "laser", "--port", "/nonexistent/tty", "on", "1000", "--seconds", "1e12");
        Add("HZ abc: is not a whole number", "laser", "--port", "/nonexistent/tty", "on", "abc");
        Add("is the same as gate.offCommand \"PING\"", "laser", "--port", "/nonexistent/tty", "on", "1000", "--profile", "@profile:off-ping");
        Add("gate must not be null", "laser", "--port", "/nonexistent/tty", "status", "--profile", "@profile:gate-null");
        Add("gate.watchdogMs must be 50..60000 ms", "simulator", "--stage-port", "/nonexistent/a", "--laser-port", "/nonexistent/b", "--profile", "@profile:watchdog-0");
        Add("--stage-port", "simulator", "--laser-port", "/nonexistent/b");

        // pattern scan-offset: the sizes, the speeds, the file and where the blocks go.
        Add("--out", "pattern", "scan-offset");
        Add("give a .png or .bmp file", "pattern", "scan-offset", "--out", "@dir");
        Add("give a .png or .bmp file", "pattern", "scan-offset", "--out", "scan.txt");
        Add("0 bars: give 1..100", "pattern", "scan-offset", "--out", "@out", "--bars", "0");
        Add("pitch 0 µm must be a finite number above 0", "pattern", "scan-offset", "--out", "@out", "--pitch-um", "0");
        Add("bar width 1 µm is less than one pixel of 25 µm", "pattern", "scan-offset", "--out", "@out", "--bar-width-um", "1");
        Add("--speed-mm-s 100: outside what the stage takes", "pattern", "scan-offset", "--out", "@out", "--speed-mm-s", "100");
        Add("--speed-mm-s 1, 1: each speed once", "pattern", "scan-offset", "--out", "@out", "--speed-mm-s", "1", "--speed-mm-s", "1");
        Add("past the travel", "pattern", "scan-offset", "--out", "@out", "--origin-mm", "59,10");
        Add("scanOffsets[0].speedMmPerS must be a finite speed above 0", "pattern", "scan-offset", "--out", "@out", "--profile", "@profile:scan-speed-0");

        // machine latency: the count, the profile to write, the machine.
        Add("--count 0: must be 1..100000", "machine", "latency", "--simulate", "--count", "0");
        Add("--count -3: must be 1..100000", "machine", "latency", "--simulate", "--count", "-3");
        Add("--count 1000000: must be 1..100000", "machine", "latency", "--simulate", "--count", "1000000");
        Add("--write needs --profile FILE", "machine", "latency", "--simulate", "--write");
        Add("give the machine", "machine", "latency");
        Add("gate.watchdogMs must be 50..60000 ms", "machine", "latency", "--simulate", "--profile", "@profile:watchdog-0", "--write");

        // Logs, previews, the benchmark, and what is not a command at all.
        Add("named pipe (FIFO)", "log", "show", "@fifo");
        Add("is a folder", "log", "show", "@dir");
        Add("no such run log", "log", "show", "@missing");
        Add("@text", "log", "show", "@text");
        Add("--max-px 0: must be between 16 and 4096", "preview", "@qr", "--width-mm", "1", "--out", "@out", "--max-px", "0");
        Add("--max-px 100000: must be between 16 and 4096", "preview", "@qr", "--width-mm", "1", "--out", "@out", "--max-px", "100000");
        Add("named pipe (FIFO)", "preview", "@fifo", "--width-mm", "1", "--out", "@out");
        Add("--speed-mm-s 100: outside what the stage takes", "preview", "@qr", "--width-mm", "1", "--out", "@out", "--speed-mm-s", "100");
        Add("--size 10: must be between 64 and 60000", "bench", "--size", "10");
        Add("--size 1000000: must be between 64 and 60000", "bench", "--size", "1000000");
        Add("--out @fifo: is a named pipe (FIFO)", "mask", "@qr", "--out", "@fifo");
        Add("--out @dir: is a folder", "mask", "@qr", "--out", "@dir");
        Add("--out @fifo: is a named pipe (FIFO)", "preview", "@qr", "--width-mm", "1", "--out", "@fifo");
        Add("--mask-out @dev: is a character device", "preview", "@qr", "--width-mm", "1", "--out", "@out", "--mask-out", "@dev");
        Add("--segments @fifo: is a named pipe (FIFO)", "plan", "@qr", "--width-mm", "1", "--segments", "@fifo");
        Add("--burned @fifo: is a named pipe (FIFO)", "engrave", "@qr", "--width-mm", "1", "--simulate", "--log-dir", "@logdir", "--burned", "@fifo");
        Add("named pipe (FIFO)", "bench", "--image", "@fifo");
        Add("Unrecognized command or argument 'frobnicate'", "frobnicate");
        ValuesByWhatTheyAre.AddRows(Add);
        Add("--bogus", "plan", "@qr", "--width-mm", "1", "--bogus");
        return rows;
    }
}

/// <summary>The files the table's tokens stand for, made once per test run in a temporary folder.</summary>
public sealed class BadInputFiles
{
    private static readonly Lazy<BadInputFiles> Shared = new(() => new BadInputFiles());

    private readonly Dictionary<string, string> _tokens = new(StringComparer.Ordinal);

    private static void DeleteFolder(string folder)
    {
        try
        {
            Directory.Delete(folder, recursive: true);
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException)
        {
            // Left for the system's temp cleaning.
        }
    }

    private BadInputFiles()
    {
        var folder = Directory.CreateTempSubdirectory("le-bad-input-").FullName;
        AppDomain.CurrentDomain.ProcessExit += (_, _) => DeleteFolder(folder);
        var qr = Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");
        _tokens["@qr"] = qr;
        _tokens["@zprofile"] = Path.Combine(CliHarness.RepositoryRoot, "assets", "profiles", "three-axis.json");
        _tokens["@dir"] = folder;
        _tokens["@dev"] = "/dev/null";
        _tokens["@missing"] = Path.Combine(folder, "missing.bmp");
        _tokens["@out"] = Path.Combine(folder, "out.png");
        _tokens["@logdir"] = Path.Combine(folder, "logs");
        _tokens["@empty"] = Write(folder, "empty.bmp", []);
        _tokens["@text"] = Write(folder, "text.json", "this is not an image, nor a log"u8.ToArray());

        // The QR code's BMP with the last rows of its pixel data cut off: the headers are whole, the pixels are not.
        var bmp = File.ReadAllBytes(qr);
        _tokens["@truncated"] = Write(folder, "truncated.bmp", bmp[..(bmp.Length - 40)]);

        var fifo = Path.Combine(folder, "fifo.bmp");
        using (var mkfifo = Process.Start(new ProcessStartInfo("mkfifo", fifo) { UseShellExecute = false })!)
        {
            mkfifo.WaitForExit();
        }

        _tokens["@fifo"] = fifo;
        foreach (var (name, (json, _)) in BadInputTable.Profiles)
        {
            _tokens[$"@profile:{name}"] = Write(folder, $"profile-{name}.json", System.Text.Encoding.UTF8.GetBytes(json));
        }

        var store = new RunLogStore(Path.Combine(folder, "written-logs"));
        var record = Record(qr);
        _tokens["@log"] = store.Write(record with { SampleId = "good" }).JsonPath;
        _tokens["@log-watchdog-0"] = store.Write(record with
        {
            SampleId = "watchdog-0",
            Profile = MachineProfile.Default with { Gate = new LaserGateProfile { WatchdogMs = 0 } },
        }).JsonPath;
        _tokens["@log-fast"] = store.Write(record with { SampleId = "fast", Process = record.Process with { BurnSpeedMmPerS = 100 } }).JsonPath;
        ValuesByWhatTheyAre.WriteFiles(folder, _tokens["@log"], _tokens);
    }

    public static BadInputFiles Instance => Shared.Value;

    /// <summary>The arguments with every token replaced by its file (the longest tokens first, so @log-fast is not read as @log).</summary>
    public string[] Resolve(string[] args) =>
        [.. args.Select(arg => _tokens.Keys.OrderByDescending(k => k.Length).Aggregate(arg, (text, token) => text.Replace(token, _tokens[token], StringComparison.Ordinal)))];

    /// <summary>The expected fragment with tokens replaced too (a fragment may name the file).</summary>
    public string ResolveFragment(string fragment) => Resolve([fragment])[0];

    private static string Write(string folder, string name, byte[] bytes)
    {
        var path = Path.Combine(folder, name);
        File.WriteAllBytes(path, bytes);
        return path;
    }

    private static RunRecord Record(string image)
    {
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = image, Size = SizeSpec.Width(1) });
        return RunRecord.ForJob(job, PreparedJob.HashFile(image), DateTimeOffset.Now) with
        {
            Outcome = RunOutcome.Completed,
            RunsDone = job.Statistics.BurnRuns,
            RowsDone = job.Statistics.Rows,
        };
    }
}
