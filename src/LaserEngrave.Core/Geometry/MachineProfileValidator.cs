using System.Globalization;
using System.Text.Json;

namespace LaserEngrave.Core.Geometry;

/// <summary>The rules a machine profile must meet before anything is opened with it: each value within what the devices take.</summary>
/// <remarks>
/// Zaber T-series firmware 5.xx (docs/zaber-protocol.md): speed data 1..32767 x 9.375 microsteps/s, acceleration data
/// 1..32767 x 11250 microsteps/s² (0 would mean "no ramp"), positions 0..16 777 215 microsteps, 9600 baud only. The laser
/// gate (docs/laser-gate-protocol.md): frequency 0..100000 whole Hz, watchdog 50..60000 ms (a frequency-only gate: none,
/// said as 0). Used by the CLI and the app.
/// </remarks>
public static class MachineProfileValidator
{
    /// <summary>Watchdog time the gate takes, ms; 0 (no watchdog) is refused: a burning laser must stop on its own when the host falls silent.</summary>
    public const int MinWatchdogMs = 50;

    public const int MaxWatchdogMs = 60000;

    /// <summary>Highest frequency the default gate protocol takes (FREQ 0..100000).</summary>
    public const int GateFrequencyLimitHz = 100000;

    /// <summary>Largest Maximum Position a Zaber device takes (Set Maximum Position data).</summary>
    public const long MaxPositionMicrosteps = 16_777_215;

    /// <summary>Longest gate reply wait accepted, ms.</summary>
    public const int MaxTimeoutMs = 60000;

    private static readonly int[] BaudRates = [300, 600, 1200, 2400, 4800, 9600, 14400, 19200, 38400, 57600, 115200];

    /// <summary>Throws a <see cref="ProfileException"/> "SOURCE: FIELD ..." naming the first unusable field.</summary>
    public static void Validate(MachineProfile profile, string source = "profile")
    {
        ArgumentNullException.ThrowIfNull(profile);
        var problems = Problems(profile);
        if (problems.Count > 0)
        {
            throw new ProfileException($"{source}: {problems[0]}");
        }
    }

    private const double MaxLatencyMs = 100;

    /// <summary>Largest edge tolerance a profile may give, µm: a tenth of a millimetre is no edge any more.</summary>
    public const double MaxEdgeToleranceUm = 100;

    /// <summary>Every problem of <paramref name="profile"/>, each "field: what is wrong (got value)", in the order of the file.</summary>
    public static IReadOnlyList<string> Problems(MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var problems = new List<string>();
        void Require(bool ok, string what)
        {
            if (!ok)
            {
                problems.Add(what);
            }
        }

        // A section given as null in the JSON ("gate": null) arrives here as null despite the type.
        Require(!string.IsNullOrWhiteSpace(profile.Name), "name must not be empty");
        var sections = new (string Name, object? Value)[] { ("x", profile.X), ("y", profile.Y), ("gate", profile.Gate), ("latency", profile.Latency) };
        foreach (var (name, value) in sections.Where(s => s.Value is null))
        {
            problems.Add($"{name} must not be null: give the section or leave it out for the defaults");
        }

        if (problems.Count > 0)
        {
            return problems;
        }

        var axes = new List<(string Name, AxisProfile Axis)> { ("x", profile.X), ("y", profile.Y) };
        if (profile.Z is { } zAxis)
        {
            axes.Add(("z", zAxis));
        }

        foreach (var (name, axis) in axes)
        {
            Require(axis.DeviceNumber is >= 1 and <= 254, $"{name}.deviceNumber must be 1..254 (got {axis.DeviceNumber})");
            Require(axis.MicrostepUm is > 0 and <= 100, $"{name}.microstepUm must be above 0 and at most 100 µm (got {N(axis.MicrostepUm)})");
            if (!(axis.MicrostepUm is > 0 and <= 100))
            {
                continue;
            }

            Require(
                axis.TravelMm > 0 && double.IsFinite(axis.TravelMm) && axis.TravelMicrosteps <= MaxPositionMicrosteps,
                $"{name}.travelMm must be above 0 and at most {N(StageUnits.MicrostepsToMm(MaxPositionMicrosteps, axis.MicrostepUm))} mm, the largest Maximum Position a Zaber device takes (got {N(axis.TravelMm)})");
            var minSpeed = StageUnits.MicrostepsToMm(StageUnits.SpeedUnitMicrostepsPerS, axis.MicrostepUm);
            var maxSpeed = minSpeed * StageUnits.MaxSettingData;
            Require(
                axis.MaxSpeedMmPerS >= minSpeed && axis.MaxSpeedMmPerS <= maxSpeed,
                $"{name}.maxSpeedMmPerS must be {N(minSpeed)}..{N(maxSpeed)} mm/s, the device's target speed range (got {N(axis.MaxSpeedMmPerS)})");
            var minAcceleration = StageUnits.MicrostepsToMm(StageUnits.AccelerationUnitMicrostepsPerS2, axis.MicrostepUm);
            var maxAcceleration = minAcceleration * StageUnits.MaxSettingData;
            Require(
                axis.MaxAccelerationMmPerS2 >= minAcceleration && axis.MaxAccelerationMmPerS2 <= maxAcceleration,
                $"{name}.maxAccelerationMmPerS2 must be {N(minAcceleration)}..{N(maxAcceleration)} mm/s², the device's acceleration range (got {N(axis.MaxAccelerationMmPerS2)})");
        }

        if (problems.Count == 0 && EqualMicrosteps(profile) is { } unequal)
        {
            problems.Add(unequal);
        }

        Require(profile.X.DeviceNumber != profile.Y.DeviceNumber, $"x.deviceNumber and y.deviceNumber cannot both be {profile.X.DeviceNumber}");
        if (profile.Z is { } z)
        {
            CheckZ(profile, z, problems);
        }

        Require(profile.StageBaudRate == 9600, $"stageBaudRate must be 9600: Zaber T-series devices speak only 9600 baud (got {profile.StageBaudRate})");
        Require(profile.SpotDiameterUm > 0 && double.IsFinite(profile.SpotDiameterUm), $"spotDiameterUm must be a finite number above 0 (got {N(profile.SpotDiameterUm)})");

        var gate = profile.Gate;
        Require(gate.MaxFrequencyHz is >= 1 and <= GateFrequencyLimitHz, $"gate.maxFrequencyHz must be 1..{GateFrequencyLimitHz} Hz, the gate's FREQ range (got {gate.MaxFrequencyHz})");
        if (problems.Count == 0)
        {
            var limits = MachineLimits.Of(profile);
            Require(limits.SpeedAllowed(profile.BurnSpeedMmPerS), $"burnSpeedMmPerS must be {limits.SpeedRange} (got {N(profile.BurnSpeedMmPerS)})");
            Require(limits.SpeedAllowed(profile.TravelSpeedMmPerS), $"travelSpeedMmPerS must be {limits.SpeedRange} (got {N(profile.TravelSpeedMmPerS)})");
            Require(limits.AccelerationAllowed(profile.AccelerationMmPerS2), $"accelerationMmPerS2 must be {limits.AccelerationRange} (got {N(profile.AccelerationMmPerS2)})");
            Require(limits.FrequencyAllowed(profile.LaserFrequencyHz), $"laserFrequencyHz must be 1..{gate.MaxFrequencyHz} Hz, up to gate.maxFrequencyHz (got {N(profile.LaserFrequencyHz)})");
            Require(
                profile.MaxFrameFrequencyHz >= 1 && profile.MaxFrameFrequencyHz <= gate.MaxFrequencyHz,
                $"maxFrameFrequencyHz must be 1..{gate.MaxFrequencyHz} Hz, up to gate.maxFrequencyHz (got {profile.MaxFrameFrequencyHz})");
        }

        Require(BaudRates.Contains(gate.BaudRate), $"gate.baudRate must be one of {string.Join(", ", BaudRates)} (got {gate.BaudRate})");
        Require(gate.TimeoutMs is >= 1 and <= MaxTimeoutMs, $"gate.timeoutMs must be 1..{MaxTimeoutMs} ms (got {gate.TimeoutMs})");
        if (gate.CountsBursts)
        {
            Require(
                gate.WatchdogMs is >= MinWatchdogMs and <= MaxWatchdogMs,
                $"gate.watchdogMs must be {MinWatchdogMs}..{MaxWatchdogMs} ms: the watchdog switches the laser off when the host falls silent, and a run never burns without it (got {gate.WatchdogMs})");
            Require(!gate.NeverReplies, "gate.neverReplies must be false for a countedBurst gate: its replies prove each burst and its watchdog; only a frequencyOnly gate may never reply");
        }
        else
        {
            // A gate without a watchdog must say so in its profile, so that nobody takes the default 1000 ms for a promise.
            Require(
                gate.WatchdogMs == 0,
                $"gate.watchdogMs must be 0 for a frequencyOnly gate: such a gate has no watchdog, and the profile must say so (got {gate.WatchdogMs})");
        }

        CheckGateStrings(gate, problems);
        Require(
            profile.EdgeToleranceUm is > 0 and <= MaxEdgeToleranceUm,
            $"edgeToleranceUm must be above 0 and at most {MaxEdgeToleranceUm} µm: how far a late switching may land from its edge (got {N(profile.EdgeToleranceUm)})");
        var latency = profile.Latency;
        foreach (var (name, ms) in new[]
                 {
                     ("stageMs", latency.StageMs), ("stageJitterMs", latency.StageJitterMs), ("gateMs", latency.GateMs),
                     ("gateJitterMs", latency.GateJitterMs), ("gateProcessingMs", latency.GateProcessingMs), ("gateProcessingJitterMs", latency.GateProcessingJitterMs),
                     ("hostLatenessMs", latency.HostLatenessMs), ("hostLatenessTailMs", latency.HostLatenessTailMs),
                 })
        {
            Require(ms is >= 0 and <= MaxLatencyMs, $"latency.{name} must be 0..{MaxLatencyMs} ms (got {N(ms)})");
        }

        CheckScanOffsets(profile.ScanOffsets, problems);
        if (profile.Camera is { } camera)
        {
            CheckCamera(camera, problems);
        }
        try
        {
            profile.Calibration?.Validate("calibration");
        }
        catch (CalibrationException ex)
        {
            problems.Add(ex.Message);
        }

        return problems;
    }

    /// <summary>
    /// Null when X and Y have the same microstep. A pixel pitch, a dot pitch and a drawing's points are whole microsteps on
    /// both axes at once, so the planners take only equal axes: a profile that differs is refused when it is read, not
    /// when the first job is planned.
    /// </summary>
    public static string? EqualMicrosteps(MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        return profile.X.MicrostepUm == profile.Y.MicrostepUm ? null
            // Written in full: two microsteps that differ in the sixth digit would read the same shortened.
            : $"x.microstepUm {profile.X.MicrostepUm.ToString(CultureInfo.InvariantCulture)} and y.microstepUm {profile.Y.MicrostepUm.ToString(CultureInfo.InvariantCulture)} must be equal: a pitch in whole microsteps needs the same microstep on both axes";
    }

    // The focus axis beyond what every axis must meet: its own device number, a move speed it takes, and limits inside its travel around the visible focus.
    private static void CheckZ(MachineProfile profile, ZAxisProfile z, List<string> problems)
    {
        foreach (var (name, other) in new[] { ("x", profile.X), ("y", profile.Y) })
        {
            if (z.DeviceNumber == other.DeviceNumber)
            {
                problems.Add($"z.deviceNumber and {name}.deviceNumber cannot both be {z.DeviceNumber}: the focus axis is a device of its own on the chain");
            }
        }

        if (problems.Count > 0)
        {
            return;
        }

        var minSpeed = StageUnits.MicrostepsToMm(StageUnits.SpeedUnitMicrostepsPerS, z.MicrostepUm);
        if (!(z.SpeedMmPerS >= minSpeed && z.SpeedMmPerS <= z.MaxSpeedMmPerS))
        {
            problems.Add($"z.speedMmPerS must be {N(minSpeed)}..{N(z.MaxSpeedMmPerS)} mm/s, one speed unit up to z.maxSpeedMmPerS (got {N(z.SpeedMmPerS)})");
        }

        if (!(z.MinMm >= 0 && z.MinMm < z.TravelMm))
        {
            problems.Add($"z.minMm must be 0 or more and below z.travelMm {N(z.TravelMm)} mm (got {N(z.MinMm)})");
        }
        else if (z.MaxMm is { } max && !(max > z.MinMm && max <= z.TravelMm))
        {
            problems.Add($"z.maxMm must be above z.minMm {N(z.MinMm)} mm and at most z.travelMm {N(z.TravelMm)} mm (got {N(max)})");
        }
        else if (!(z.FocusMm >= z.MinMm && z.FocusMm <= z.UpperMm))
        {
            problems.Add($"z.focusMm must be within z.minMm..z.maxMm {N(z.MinMm)}..{N(z.UpperMm)} mm (got {N(z.FocusMm)})");
        }
    }

    /// <summary>Largest camera image side the app takes, pixels.</summary>
    public const int MaxCameraSidePx = 8192;

    // The camera's figures: an image size a grabber gives, a scale from a microscope to a macro lens, the spot inside the image.
    private static void CheckCamera(CameraProfile camera, List<string> problems)
    {
        var before = problems.Count;
        void Require(bool ok, string what)
        {
            if (!ok)
            {
                problems.Add(what);
            }
        }

        Require(camera.WidthPx is >= 16 and <= MaxCameraSidePx, $"camera.widthPx must be 16..{MaxCameraSidePx} pixels (got {camera.WidthPx})");
        Require(camera.HeightPx is >= 16 and <= MaxCameraSidePx, $"camera.heightPx must be 16..{MaxCameraSidePx} pixels (got {camera.HeightPx})");
        Require(camera.UmPerPixel is > 0 and <= 1000, $"camera.umPerPixel must be above 0 and at most 1000 µm on the sample per camera pixel (got {N(camera.UmPerPixel)})");
        Require(camera.RotationDeg is > -180 and <= 180, $"camera.rotationDeg must be above -180 and at most 180 degrees (got {N(camera.RotationDeg)})");
        if (problems.Count > before)
        {
            return;
        }

        var halfWidthUm = camera.WidthPx * camera.UmPerPixel / 2;
        var halfHeightUm = camera.HeightPx * camera.UmPerPixel / 2;
        Require(Math.Abs(camera.SpotOffsetXUm) < halfWidthUm, $"camera.spotOffsetXUm must lie inside the image, less than {N(halfWidthUm)} µm from its centre either way (got {N(camera.SpotOffsetXUm)})");
        Require(Math.Abs(camera.SpotOffsetYUm) < halfHeightUm, $"camera.spotOffsetYUm must lie inside the image, less than {N(halfHeightUm)} µm from its centre either way (got {N(camera.SpotOffsetYUm)})");
        if (camera.Calibration is { } c)
        {
            Require(c.UmPerPixel is > 0 and <= 1000, $"camera.calibration.umPerPixel must be above 0 and at most 1000 µm (got {N(c.UmPerPixel)})");
            Require(c.RotationDeg is > -180 and <= 180, $"camera.calibration.rotationDeg must be above -180 and at most 180 degrees (got {N(c.RotationDeg)})");
            Require(c.SpotXPx >= 0 && c.SpotXPx <= camera.WidthPx - 1, $"camera.calibration.spotXPx must lie inside the image, 0..{camera.WidthPx - 1} (got {N(c.SpotXPx)})");
            Require(c.SpotYPx >= 0 && c.SpotYPx <= camera.HeightPx - 1, $"camera.calibration.spotYPx must lie inside the image, 0..{camera.HeightPx - 1} (got {N(c.SpotYPx)})");
            Require(c.ResidualUm >= 0 && double.IsFinite(c.ResidualUm), $"camera.calibration.residualUm must be a finite number, 0 or more (got {N(c.ResidualUm)})");
        }
    }

    // Speeds in increasing order, each once, so the table reads one way; offsets bounded, so a typo (mm for µm) is caught.
    private static void CheckScanOffsets(IReadOnlyList<ScanOffset>? table, List<string> problems)
    {
        if (table is null)
        {
            return;
        }

        for (var i = 0; i < table.Count; i++)
        {
            var entry = table[i];
            var name = $"scanOffsets[{i}]";
            if (entry is null)
            {
                problems.Add($"{name} must not be null: give speedMmPerS and offsetUm");
                return;
            }

            if (!(entry.SpeedMmPerS > 0) || !double.IsFinite(entry.SpeedMmPerS))
            {
                problems.Add($"{name}.speedMmPerS must be a finite speed above 0 mm/s (got {N(entry.SpeedMmPerS)})");
                return;
            }

            if (!double.IsFinite(entry.OffsetUm) || Math.Abs(entry.OffsetUm) > ScanOffset.MaxOffsetUm)
            {
                problems.Add($"{name}.offsetUm must be finite and at most {N(ScanOffset.MaxOffsetUm)} µm either way (got {N(entry.OffsetUm)})");
                return;
            }

            if (i > 0 && table[i - 1] is { } previous && !(entry.SpeedMmPerS > previous.SpeedMmPerS))
            {
                problems.Add($"{name}.speedMmPerS must be above scanOffsets[{i - 1}].speedMmPerS {N(previous.SpeedMmPerS)} mm/s: list the speeds in increasing order, each once (got {N(entry.SpeedMmPerS)})");
                return;
            }
        }
    }

    /// <summary>One line for a profile the JSON reader refused: the field (from the JSON path), what is wrong there and where (line and column from 1).</summary>
    /// <param name="text">The profile's text, when at hand: a number written as text ("12,5") is then named with how to write it.</param>
    public static string DescribeJsonError(JsonException ex, string? text = null)
    {
        ArgumentNullException.ThrowIfNull(ex);
        var field = ex.Path is { Length: > 0 } path ? path.TrimStart('$').TrimStart('.') : string.Empty;
        var line = IO.JsonProblem.Position(ex) is { } position ? $" ({position})" : string.Empty;
        if (ex.Message.Contains("could not be mapped", StringComparison.Ordinal))
        {
            var name = ex.Message.Split('\'') is { Length: > 2 } parts ? parts[1] : "?";
            var where = field.Length == 0 ? name : field.EndsWith(name, StringComparison.Ordinal) ? field : $"{field}.{name}";
            return $"{where} is not a field of the machine profile{line}: check its spelling (names are camelCase, e.g. watchdogMs); docs/machine-profile.md lists them";
        }

        if (!ex.Message.Contains("could not be converted", StringComparison.Ordinal))
        {
            return IO.JsonProblem.Syntax(ex);
        }

        return field.Length == 0
            ? $"not a valid machine profile{line}: expected a JSON object"
            : $"{field} has a value of the wrong type or out of range for it{line}{IO.JsonProblem.NumberHint(text, ex.Path)}";
    }

    private static void CheckGateStrings(LaserGateProfile gate, List<string> problems)
    {
        // Every command is told from the others by how it begins (replies echo it), so none may equal another or begin with it.
        // A frequency-only gate is sent only its frequency, its off and (when it answers and has one) its identify command;
        // the others are never sent, so they are not checked, and its off may be the frequency command at 0 ("FREQ 0").
        var frequencyOnly = !gate.CountsBursts;
        var commands = new (string Field, string? Value, int Placeholders)[]
        {
            ("identifyCommand", gate.IdentifyCommand, 0),
            ("frequencyCommand", gate.FrequencyCommand, 1),
            ("offCommand", gate.OffCommand, 0),
            ("statusCommand", gate.StatusCommand, 0),
            ("keepAliveCommand", gate.KeepAliveCommand, 0),
            ("watchdogCommand", gate.WatchdogCommand, 1),
            ("burstCommand", gate.BurstCommand, 2),
            ("burstAfterCommand", gate.BurstAfterCommand, 3),
            ("capabilitiesCommand", gate.CapabilitiesCommand, 0),
        };
        if (frequencyOnly)
        {
            commands = [.. commands.Where(c => c.Field is "frequencyCommand" or "offCommand" || (c.Field == "identifyCommand" && gate.Identifies))];
        }

        var heads = new List<(string Field, string Value, string Head)>();
        foreach (var (field, value, placeholders) in commands)
        {
            if (frequencyOnly && field == "offCommand" && value is not null && gate.FrequencyCommand is not null
                && FormatProblem(gate.FrequencyCommand, 1) is null
                && string.Equals(value.Trim(), string.Format(CultureInfo.InvariantCulture, gate.FrequencyCommand, 0).Trim(), StringComparison.OrdinalIgnoreCase))
            {
                // "FREQ 0" is how a frequency-only gate is switched off: the frequency command itself, not a command of its own.
                continue;
            }

            if (string.IsNullOrWhiteSpace(value))
            {
                problems.Add($"gate.{field} must not be empty");
                continue;
            }

            if (value.AsSpan().IndexOfAny('\r', '\n') >= 0)
            {
                problems.Add($"gate.{field} must be one line (got a line break in it)");
                continue;
            }

            var head = value;
            if (placeholders > 0)
            {
                if (FormatProblem(value, placeholders) is { } bad)
                {
                    problems.Add($"gate.{field} \"{value}\" {bad}");
                    continue;
                }

                head = value[..value.IndexOf('{', StringComparison.Ordinal)];
                if (string.IsNullOrWhiteSpace(head))
                {
                    problems.Add($"gate.{field} \"{value}\" must begin with a command word, not with a value");
                    continue;
                }
            }

            heads.Add(($"gate.{field}", value, head));
        }

        for (var i = 0; i < heads.Count; i++)
        {
            for (var j = i + 1; j < heads.Count; j++)
            {
                var (a, b) = (heads[i], heads[j]);
                if (IsBurstPair(a.Field, b.Field))
                {
                    // The scheduled burst is the burst with more words (BURST {0} {1} AFTER {2}): the same head, told apart
                    // by its words. Neither may read as the other, or a switch-on meant for later would fire at once.
                    if (ReadsAs(a.Value, b.Value) || ReadsAs(b.Value, a.Value))
                    {
                        problems.Add($"{b.Field} \"{b.Value}\" reads as {a.Field} \"{a.Value}\": the scheduled burst must differ from the burst in more than its values");
                    }

                    continue;
                }

                if (a.Head.StartsWith(b.Head, StringComparison.OrdinalIgnoreCase) || b.Head.StartsWith(a.Head, StringComparison.OrdinalIgnoreCase))
                {
                    var relation = string.Equals(a.Value, b.Value, StringComparison.OrdinalIgnoreCase) ? "is the same as" : "begins like";
                    problems.Add($"{b.Field} \"{b.Value}\" {relation} {a.Field} \"{a.Value}\": each gate command must differ from the others and not begin with another");
                }
            }
        }

        var prefixes = new (string Field, string? Value)[] { ("ackPrefix", gate.AckPrefix), ("errorPrefix", gate.ErrorPrefix) };
        foreach (var (field, value) in prefixes.Where(p => string.IsNullOrWhiteSpace(p.Value)))
        {
            problems.Add($"gate.{field} must not be empty");
        }

        if (!string.IsNullOrWhiteSpace(gate.AckPrefix) && !string.IsNullOrWhiteSpace(gate.ErrorPrefix)
            && (gate.AckPrefix.StartsWith(gate.ErrorPrefix, StringComparison.OrdinalIgnoreCase) || gate.ErrorPrefix.StartsWith(gate.AckPrefix, StringComparison.OrdinalIgnoreCase)))
        {
            problems.Add($"gate.errorPrefix \"{gate.ErrorPrefix}\" and gate.ackPrefix \"{gate.AckPrefix}\" must differ and neither begin with the other");
        }

        // The replies the gate must give: read literally, or formatted with the command's values ({0}, {1}) before
        // they are compared, so a null or a placeholder past the values would fail only mid-run.
        var replies = new (string Field, string? Value, int Values, bool MayBeEmpty)[]
        {
            ("identifyReply", gate.IdentifyReply, 0, true),
            ("frequencyReply", gate.FrequencyReply, 1, false),
            ("offReply", gate.OffReply, 0, false),
            ("statusReply", gate.StatusReply, 0, false),
            ("keepAliveReply", gate.KeepAliveReply, 0, false),
            ("watchdogReply", gate.WatchdogReply, 1, false),
            ("burstReply", gate.BurstReply, 2, false),
            ("burstAfterReply", gate.BurstAfterReply, 3, false),
            ("capabilitiesReply", gate.CapabilitiesReply, 0, false),
        };
        if (frequencyOnly)
        {
            // Only the replies of the commands a frequency-only gate is sent; none at all when it never replies.
            replies = gate.NeverReplies ? [] : [.. replies.Where(r => r.Field is "frequencyReply" or "offReply" || (r.Field == "identifyReply" && gate.Identifies))];
        }

        foreach (var (field, value, count, mayBeEmpty) in replies)
        {
            if (value is null || (!mayBeEmpty && string.IsNullOrWhiteSpace(value)))
            {
                problems.Add($"gate.{field} must not be {(value is null ? "null" : "empty")}: give the gate's reply or leave the field out for the default");
            }
            else if (value.AsSpan().IndexOfAny('\r', '\n') >= 0)
            {
                problems.Add($"gate.{field} must be one line (got a line break in it)");
            }
            else if (count > 0 && ReplyTemplateProblem(value, count) is { } bad)
            {
                problems.Add($"gate.{field} \"{value}\" {bad}");
            }
        }

        if (gate.LineTerminator is not ("\n" or "\r\n" or "\r"))
        {
            problems.Add($"gate.lineTerminator must be \"\\n\", \"\\r\\n\" or \"\\r\" (got {(gate.LineTerminator is null ? "null" : JsonSerializer.Serialize(gate.LineTerminator))})");
        }
    }

    private static bool IsBurstPair(string a, string b) =>
        (a, b) is ("gate.burstCommand", "gate.burstAfterCommand") or ("gate.burstAfterCommand", "gate.burstCommand");

    /// <summary>Whether a line made from template <paramref name="line"/> is matched by template <paramref name="pattern"/>, as the gate matches it (each placeholder one word, spaces any run of whitespace, any case).</summary>
    private static bool ReadsAs(string line, string pattern)
    {
        var values = Enumerable.Range(0, 3).Select(i => (object)(1000 + i)).ToArray();
        var text = string.Format(CultureInfo.InvariantCulture, line, values);
        var regex = "^" + string.Concat(System.Text.RegularExpressions.Regex.Split(pattern.Trim(), @"(\{\d+\})").Select(part =>
            System.Text.RegularExpressions.Regex.IsMatch(part, @"^\{\d+\}$") ? @"(\S+)" : System.Text.RegularExpressions.Regex.Replace(System.Text.RegularExpressions.Regex.Escape(part), @"(\\ )+", @"\s+"))) + "$";
        return System.Text.RegularExpressions.Regex.IsMatch(text.Trim(), regex, System.Text.RegularExpressions.RegexOptions.IgnoreCase | System.Text.RegularExpressions.RegexOptions.CultureInvariant);
    }

    /// <summary>Null when a reply template formats with <paramref name="count"/> values (it need not use them all).</summary>
    private static string? ReplyTemplateProblem(string format, int count)
    {
        try
        {
            _ = string.Format(CultureInfo.InvariantCulture, format, Enumerable.Range(0, count).Select(i => (object)i).ToArray());
            return null;
        }
        catch (FormatException)
        {
            return count switch
            {
                1 => "is not a valid reply template: only {0} (the command's value) may stand in braces; double any other brace",
                2 => "is not a valid reply template: only {0} and {1} (the command's values) may stand in braces; double any other brace",
                _ => "is not a valid reply template: only {0}, {1} and {2} (the command's values) may stand in braces; double any other brace",
            };
        }
    }

    /// <summary>Null when <paramref name="format"/> formats with <paramref name="count"/> numbers and uses each of them.</summary>
    private static string? FormatProblem(string format, int count)
    {
        var values = Enumerable.Range(0, count).Select(i => (object)(1000 + i)).ToArray();
        string formatted;
        try
        {
            formatted = string.Format(CultureInfo.InvariantCulture, format, values);
        }
        catch (FormatException)
        {
            return $"is not a valid template: use {(count switch { 1 => "{0}", 2 => "{0} and {1}", _ => "{0}, {1} and {2}" })} for the value{(count > 1 ? "s" : string.Empty)} and double any other brace";
        }

        for (var i = 0; i < count; i++)
        {
            if (!format.Contains($"{{{i}", StringComparison.Ordinal))
            {
                return $"must hold {{{i}}} where the value goes";
            }
        }

        return formatted.Length > 0 ? null : "formats to nothing";
    }

    private static string N(double value) => MachineLimits.Text.N(value);
}
