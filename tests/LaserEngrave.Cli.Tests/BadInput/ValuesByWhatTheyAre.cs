using System.Text.Json.Nodes;

namespace LaserEngrave.Cli.Tests.BadInput;

/// <summary>
/// The census's rows for issue 21: a value is checked by what it is, whichever file or option it comes from (run logs,
/// job files, simulator options, drawings, output paths, decimal commas, typos). Tokens: @log:NAME is the good log with
/// one field changed, @f:NAME a file written here.
/// </summary>
public static class ValuesByWhatTheyAre
{
    /// <summary>One change to the good run log each, by token name.</summary>
    private static readonly Dictionary<string, Action<JsonObject>> Logs = new(StringComparer.Ordinal)
    {
        ["overscan-1e308"] = log => log["plan"]!["overscanMm"] = 1e308,
        ["overscan-negative"] = log => log["plan"]!["overscanMm"] = -1,
        ["overscan-text"] = log => log["plan"]!["overscanMm"] = "big",
        ["row-negative"] = log => log["stoppedAt"] = new JsonObject { ["row"] = -1, ["moveIndex"] = 0 },
        ["move-negative"] = log => log["stoppedAt"] = new JsonObject { ["row"] = 0, ["moveIndex"] = -5 },
        ["stop-x-past-travel"] = log => log["stoppedAt"] = new JsonObject { ["row"] = 0, ["moveIndex"] = 0, ["xMicrosteps"] = 999_999_999 },
        ["passes-1000"] = log => log["passes"] = 1000,
        ["passes-0"] = log => log["passes"] = 0,
        ["plan-null"] = log => log["plan"] = null,
        ["process-null"] = log => log["process"] = null,
        ["image-missing"] = log => log.Remove("image"),
        ["threshold-500"] = log => log["mask"]!["thresholdPercent"] = 500,
        ["origin-negative"] = log => log["geometry"]!["originXMm"] = -5,
        ["origin-1e308"] = log => log["geometry"]!["originYMm"] = 1e308,
        ["width-0"] = log => log["geometry"]!["size"]!["widthMm"] = 0,
        ["width-huge"] = log => log["geometry"]!["size"]!["widthMm"] = 1e9,
        ["pulses-0"] = log => log["process"]!["pulsesPerDot"] = 0,
        ["settle-huge"] = log => log["process"]!["dotSettleMs"] = 1e12,
        ["speed-1e308"] = log => log["process"]!["burnSpeedMmPerS"] = 1e308,
        ["strategy-unknown"] = log => log["plan"]!["strategy"] = "zigzag",
        ["profile-off-reply-null"] = log => log["profile"]!["gate"]!["offReply"] = null,
    };

    /// <summary>Files by name (the extension tells the reader), each with one bad value.</summary>
    private static readonly Dictionary<string, string> Files = new(StringComparer.Ordinal)
    {
        ["scale-1e308.svg"] = """<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10"><g transform="scale(1e308)"><path d="M0 0 L5 5 L5 0 Z"/></g></svg>""",
        ["coordinate-1e308.svg"] = """<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10"><path d="M0 0 L1e308 5"/></svg>""",
        ["matrix-huge.svg"] = """<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10"><path transform="matrix(1e200 0 0 1e200 0 0)" d="M0 0 L5 5"/></svg>""",
        ["translate-huge.svg"] = """<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10"><path transform="translate(1e300)" d="M0 0 L5 5"/></svg>""",
        ["line-1e308.dxf"] = "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n0\n20\n0\n11\n1e308\n21\n1\n0\nENDSEC\n0\nEOF\n",
        ["layers-2000.json"] = "{\"layers\":[" + string.Join(',', Enumerable.Repeat("{\"source\":\"QR\",\"widthMm\":1}", 2000)) + "]}",
        ["layer-width-1e400.json"] = """{"layers":[{"source":"QR","widthMm":1e400}]}""",
        ["layer-width-1e308.json"] = """{"layers":[{"source":"QR","widthMm":1e308}]}""",
        ["layer-origin-1e308.json"] = """{"layers":[{"source":"QR","widthMm":5,"originMm":[1e308,0]}]}""",
        ["layer-speed-1e308.json"] = """{"layers":[{"source":"QR","widthMm":5,"speedMmPerS":1e308}]}""",
        ["layer-passes-fraction.json"] = """{"layers":[{"source":"QR","widthMm":5,"passes":1.5}]}""",
        ["layer-width-text.json"] = """{"layers":[{"source":"QR","widthMm":"5,5"}]}""",
        ["sim-seed-text.json"] = """{"seed":"x"}""",
        ["sim-start-negative.json"] = """{"startMm":-5}""",
        ["sim-start-1e308.json"] = """{"startMm":1e308}""",
        ["sim-array.json"] = "[]",
    };

    /// <summary>Writes the files and the changed logs, adding their tokens.</summary>
    public static void WriteFiles(string folder, string goodLog, Dictionary<string, string> tokens)
    {
        var good = File.ReadAllText(goodLog);
        foreach (var (name, change) in Logs)
        {
            var log = JsonNode.Parse(good)!.AsObject();
            change(log);
            var path = Path.Combine(folder, $"log-{name}.json");
            File.WriteAllText(path, log.ToJsonString());
            tokens[$"@log:{name}"] = path;
        }

        var qr = Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");
        foreach (var (name, text) in Files)
        {
            var path = Path.Combine(folder, name);
            File.WriteAllText(path, text.Replace("\"QR\"", System.Text.Json.JsonSerializer.Serialize(qr), StringComparison.Ordinal));
            tokens[$"@f:{name}"] = path;
        }
    }

    /// <summary>The rows: each refused with exit code 2 and one line holding the fragment.</summary>
    public static void AddRows(Action<string, string[]> add)
    {
        // Run logs: every value a repeat or a resume takes is checked as the command line's would be, naming the field.
        foreach (var (name, fragment) in new[]
        {
            ("overscan-1e308", "@log:overscan-1e308: plan.overscanMm 1E+308: must be 0..60 mm (the X travel)"),
            ("overscan-negative", "plan.overscanMm -1: must be 0..60 mm"),
            ("overscan-text", "plan.overscanMm has a value of the wrong type"),
            ("passes-1000", "passes 1000: must be 1..100"),
            ("passes-0", "passes 0: must be 1..100"),
            ("plan-null", "plan must not be null"),
            ("process-null", "process must not be null"),
            ("image-missing", "a required field is missing: 'image'"),
            ("threshold-500", "mask.thresholdPercent 500: must be between 0 and 100"),
            ("origin-negative", "geometry.originXMm -5: outside the travel 0..60 mm"),
            ("origin-1e308", "geometry.originYMm 1E+308: outside the travel"),
            ("width-0", "geometry.size.widthMm 0: must be a finite number above 0"),
            ("width-huge", "geometry.size.widthMm 1E+09: at most 60 mm, the X travel"),
            ("pulses-0", "process.pulsesPerDot 0: must be 1..1000000"),
            ("settle-huge", "process.dotSettleMs 1E+12: must be 0..60000 ms"),
            ("speed-1e308", "process.burnSpeedMmPerS 1E+308: outside what the stage takes"),
            ("strategy-unknown", "plan.strategy has a value of the wrong type"),
            ("profile-off-reply-null", "profile.gate.offReply must not be null"),
        })
        {
            add(fragment, ["engrave", "--from-log", $"@log:{name}", "--simulate", "--log-dir", "@logdir"]);
        }

        foreach (var (name, fragment) in new[]
        {
            ("row-negative", "@log:row-negative: stoppedAt.row -1 must not be negative"),
            ("move-negative", "stoppedAt.moveIndex -5 must not be negative"),
            ("stop-x-past-travel", "stoppedAt.xMicrosteps 999999999 must be within the travel"),
        })
        {
            add(fragment, ["engrave", "--from-log", $"@log:{name}", "--resume", "--simulate", "--log-dir", "@logdir"]);
        }

        // Drawings: a transform or a number that takes a coordinate past any stage is refused, never planned as NaN.
        foreach (var name in new[] { "scale-1e308.svg", "coordinate-1e308.svg", "matrix-huge.svg", "translate-huge.svg", "line-1e308.dxf" })
        {
            add($"@f:{name}: a coordinate of", ["plan", $"@f:{name}", "--width-mm", "10", "--origin-mm", "5,5"]);
        }

        add("@f:scale-1e308.svg: a coordinate of infinity mm is beyond the drawing limit", ["plan", "@f:scale-1e308.svg"]);
        add("@f:scale-1e308.svg: a coordinate of", ["preview", "@f:scale-1e308.svg", "--width-mm", "10", "--out", "@out"]);

        // Job files: each layer's values against the machine, the file named.
        add("@f:layers-2000.json: 2000 layers, more than the 1000 a job file may have", ["plan", "--job", "@f:layers-2000.json"]);
        add("@f:layer-width-1e400.json: layer 1 \"layer 1\": widthMm Infinity must be a finite number above 0", ["plan", "--job", "@f:layer-width-1e400.json"]);
        add("@f:layer-width-1e308.json: layer \"layer 1\": widthMm 1E+308: at most 60 mm, the X travel", ["plan", "--job", "@f:layer-width-1e308.json"]);
        add("@f:layer-origin-1e308.json: layer \"layer 1\": originMm X 1E+308: outside the travel 0..60 mm", ["plan", "--job", "@f:layer-origin-1e308.json"]);
        add("@f:layer-speed-1e308.json: layer \"layer 1\": speedMmPerS 1E+308: outside what the stage takes", ["plan", "--job", "@f:layer-speed-1e308.json"]);
        add("passes 1.5 must be a whole number 1..100", ["plan", "--job", "@f:layer-passes-fraction.json"]);
        add("\"widthMm\" must be a number", ["plan", "--job", "@f:layer-width-text.json"]);

        // Simulator options.
        add("@f:sim-seed-text.json: field 'seed' has a value of the wrong kind", ["engrave", "@qr", "--width-mm", "1", "--simulate", "--log-dir", "@logdir", "--sim-options", "@f:sim-seed-text.json"]);
        add("startMm must be 0..1000 mm (got -5)", ["engrave", "@qr", "--width-mm", "1", "--simulate", "--log-dir", "@logdir", "--sim-options", "@f:sim-start-negative.json"]);
        add("startMm must be 0..1000 mm (got 1E+308)", ["engrave", "@qr", "--width-mm", "1", "--simulate", "--log-dir", "@logdir", "--sim-options", "@f:sim-start-1e308.json"]);
        add("not a JSON object of simulator options", ["engrave", "@qr", "--width-mm", "1", "--simulate", "--log-dir", "@logdir", "--sim-options", "@f:sim-array.json"]);

        // Output paths: a folder that is not there is found before the work, with exit 2.
        add("--out /nonexistent/dir/o.png: the folder /nonexistent/dir does not exist", ["mask", "@qr", "--out", "/nonexistent/dir/o.png"]);
        add("--out /nonexistent/dir/p.png: the folder /nonexistent/dir does not exist", ["preview", "@qr", "--width-mm", "1", "--out", "/nonexistent/dir/p.png"]);
        add("--segments /nonexistent/dir/s.csv: the folder /nonexistent/dir does not exist", ["plan", "@qr", "--width-mm", "1", "--segments", "/nonexistent/dir/s.csv"]);
        add("--out /nonexistent/dir/p.png: the folder /nonexistent/dir does not exist", ["pattern", "scan-offset", "--out", "/nonexistent/dir/p.png"]);
        add("--out /nonexistent/dir/a.png: the folder /nonexistent/dir does not exist", ["align", "@qr", "--width-mm", "5", "--mark", "1,1=21,16", "--mark", "4,4=24,19", "--out", "/nonexistent/dir/a.png"]);
        add("--out @qr/o.png: the folder @qr does not exist (it is a file)", ["mask", "@qr", "--out", "@qr/o.png"]);

        // Log folders.
        add("@qr is a file, not a log folder: `laserengrave log show @qr` shows one run log", ["log", "list", "@qr"]);
        add("@qr is a file, not a log folder", ["log", "list", "--log-dir", "@qr"]);
        add("@missing: no such log folder", ["log", "list", "--log-dir", "@missing"]);

        // Numbers as typed: one decimal mark, never a thousands separator, pairs that read one way only.
        add("--width-mm 5,5,5: has more than one decimal mark", ["plan", "@qr", "--width-mm", "5,5,5"]);
        add("--width-mm 1.000,5: has more than one decimal mark", ["plan", "@qr", "--width-mm", "1.000,5"]);
        add("--width-mm 1e400: is too large", ["plan", "@qr", "--width-mm", "1e400"]);
        add("--width-mm 0: must be a finite number above 0", ["plan", "@qr", "--width-mm", "-0"]);
        add("--width-mm : is empty", ["plan", "@qr", "--width-mm", ""]);
        add("--origin-mm 5,5,10,2: could be read more than one way; write X,Y with decimal points (5.5,10.2) or X;Y with decimal commas (5,5;10,2)", ["plan", "@qr", "--width-mm", "1", "--origin-mm", "5,5,10,2"]);
        add("--origin-mm 5,5;10,2;1: expected two numbers", ["plan", "@qr", "--width-mm", "1", "--origin-mm", "5,5;10,2;1"]);
        add("--pulses-per-dot 2,5: takes a whole number", ["plan", "@qr", "--width-mm", "1", "--mode", "dots", "--pulses-per-dot", "2,5"]);
        add("--dot-pitch-microsteps 1.000: could be 1 or 1000: write 1000 or 1.0", ["plan", "@qr", "--width-mm", "1", "--mode", "dots", "--dot-pitch-microsteps", "1.000"]);
        add("--mark 1,1,1=21,16: the job's point '1,1,1' could be read more than one way", ["align", "@qr", "--width-mm", "5", "--mark", "1,1,1=21,16", "--mark", "4,4=24,19", "--out", "@out"]);
        add("--rows speed=0,5;x: 'x' is not a number", ["sweep", "--rows", "speed=0,5;x", "--simulate", "--log-dir", "@logdir"]);
        add("--x 16=16,0,08: the measured 16,0,08 has more than one decimal mark", ["calibrate", "solve", "--profile", "@zprofile", "--x", "16=16,0,08", "--y", "16=16"]);
        add("--speed-mm-s 1,2,3: has more than one decimal mark", ["pattern", "scan-offset", "--out", "@out", "--speed-mm-s", "1,2,3"]);

        // System.CommandLine's own words: a typo gets "did you mean", a bad value no .NET type name.
        add("Unrecognized command or argument 'plna'. (did you mean plan?)", ["plna", "@qr"]);
        add("Unrecognized command or argument '--widht-mm'. (did you mean --width-mm?)", ["plan", "@qr", "--widht-mm", "5"]);
        add("Unrecognized command or argument 'lsit'. (did you mean list?)", ["log", "lsit"]);
    }
}
