using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Geometry;

public class MachineProfileValidatorTests
{
    /// <summary>A profile file with one field set badly, and the field the one-line error must name.</summary>
    public static TheoryData<string, string> BadProfiles => new()
    {
        { """{ "gate": null }""", "gate must not be null" },
        { """{ "x": null }""", "x must not be null" },
        { """{ "y": null }""", "y must not be null" },
        { """{ "name": null }""", "name must not be empty" },
        { """{ "gate": { "watchdogMs": 0 } }""", "gate.watchdogMs must be 50..60000 ms" },
        { """{ "gate": { "watchdogMs": 49 } }""", "gate.watchdogMs must be 50..60000 ms" },
        { """{ "gate": { "watchdogMs": 60001 } }""", "gate.watchdogMs must be 50..60000 ms" },
        { """{ "gate": { "offCommand": "PING" } }""", "gate.keepAliveCommand \"PING\" is the same as gate.offCommand \"PING\"" },
        { """{ "gate": { "keepAliveCommand": "OFF" } }""", "gate.keepAliveCommand \"OFF\" is the same as gate.offCommand" },
        { """{ "gate": { "offCommand": "FREQ 0" } }""", "gate.offCommand \"FREQ 0\" begins like gate.frequencyCommand" },
        { """{ "gate": { "statusCommand": "STATE" , "offCommand": "STATE?OFF" } }""", "begins like" },
        { """{ "gate": { "offCommand": "" } }""", "gate.offCommand must not be empty" },
        { """{ "gate": { "identifyCommand": null } }""", "gate.identifyCommand must not be empty" },
        { """{ "gate": { "frequencyCommand": "FREQ" } }""", "gate.frequencyCommand \"FREQ\" must hold {0}" },
        { """{ "gate": { "frequencyCommand": "FREQ {1}" } }""", "gate.frequencyCommand \"FREQ {1}\" is not a valid template" },
        { """{ "gate": { "burstCommand": "BURST {0}" } }""", "gate.burstCommand \"BURST {0}\" must hold {1}" },
        { """{ "gate": { "burstAfterCommand": "BURST {0} {1}" } }""", "gate.burstAfterCommand \"BURST {0} {1}\" must hold {2}" },
        { """{ "gate": { "burstAfterCommand": "BURST {0} {1} {2}", "burstCommand": "BURST {0} {1} AFTER" } }""", "the scheduled burst must differ from the burst in more than its values" },
        { """{ "gate": { "burstAfterCommand": "PING {0} {1} AFTER {2}" } }""", "gate.burstAfterCommand \"PING {0} {1} AFTER {2}\" begins like gate.keepAliveCommand" },
        { """{ "gate": { "capabilitiesCommand": "STATE?" } }""", "is the same as gate.statusCommand" },
        { """{ "gate": { "burstAfterReply": "BURST {3}" } }""", "gate.burstAfterReply \"BURST {3}\" is not a valid reply template: only {0}, {1} and {2}" },
        { """{ "gate": { "capabilitiesReply": "" } }""", "gate.capabilitiesReply must not be empty" },
        { """{ "gate": { "watchdogCommand": "{0} WDOG" } }""", "gate.watchdogCommand \"{0} WDOG\" must begin with a command word" },
        { """{ "gate": { "offCommand": "OFF\nNOW" } }""", "gate.offCommand must be one line" },
        { """{ "gate": { "ackPrefix": "" } }""", "gate.ackPrefix must not be empty" },
        { """{ "gate": { "errorPrefix": "OK" } }""", "gate.errorPrefix \"OK\" and gate.ackPrefix \"OK\" must differ" },
        { """{ "gate": { "lineTerminator": ";" } }""", "gate.lineTerminator must be" },
        { """{ "gate": { "offReply": null } }""", "gate.offReply must not be null" },
        { """{ "gate": { "burstReply": null } }""", "gate.burstReply must not be null" },
        { """{ "gate": { "watchdogReply": "FREQ {5}" } }""", "gate.watchdogReply \"FREQ {5}\" is not a valid reply template: only {0} (the command's value) may stand in braces" },
        { """{ "gate": { "burstReply": "BURST {2}" } }""", "gate.burstReply \"BURST {2}\" is not a valid reply template: only {0} and {1}" },
        { """{ "gate": { "statusReply": " " } }""", "gate.statusReply must not be empty" },
        { """{ "gate": { "keepAliveReply": "PONG\r" } }""", "gate.keepAliveReply must be one line" },
        { """{ "gate": { "timeoutMs": 0 } }""", "gate.timeoutMs must be 1..60000 ms" },
        { """{ "gate": { "baudRate": 12345 } }""", "gate.baudRate must be one of" },
        { """{ "gate": { "maxFrequencyHz": 200000 } }""", "gate.maxFrequencyHz must be 1..100000 Hz" },
        { """{ "gate": { "maxFrequencyHz": 500 } }""", "laserFrequencyHz must be 1..500 Hz" },
        { """{ "laserFrequencyHz": 0.2 }""", "laserFrequencyHz must be 1..100000 Hz" },
        { """{ "laserFrequencyHz": 1e12 }""", "laserFrequencyHz must be 1..100000 Hz" },
        { """{ "maxFrameFrequencyHz": 0 }""", "maxFrameFrequencyHz must be 1..100000 Hz" },
        { """{ "burnSpeedMmPerS": 5 }""", "burnSpeedMmPerS must be 0.00093..4 mm/s" },
        { """{ "travelSpeedMmPerS": 0 }""", "travelSpeedMmPerS must be 0.00093..4 mm/s" },
        { """{ "accelerationMmPerS2": 1 }""", "accelerationMmPerS2 must be 1.11621..200 mm/s²" },
        { """{ "accelerationMmPerS2": 500 }""", "accelerationMmPerS2 must be 1.11621..200 mm/s²" },
        { """{ "x": { "deviceNumber": 1, "maxSpeedMmPerS": 40 } }""", "x.maxSpeedMmPerS must be 0.00093..30.47907 mm/s" },
        { """{ "y": { "deviceNumber": 2, "maxAccelerationMmPerS2": 0 } }""", "y.maxAccelerationMmPerS2 must be 1.11621..36574.88379 mm/s²" },
        { """{ "x": { "deviceNumber": 1, "travelMm": 2000 } }""", "x.travelMm must be above 0 and at most 1664.6143 mm" },
        { """{ "x": { "deviceNumber": 1, "travelMm": 0 } }""", "x.travelMm must be above 0" },
        { """{ "x": { "deviceNumber": 0 } }""", "x.deviceNumber must be 1..254" },
        { """{ "y": { "deviceNumber": 1 } }""", "x.deviceNumber and y.deviceNumber cannot both be 1" },
        { """{ "x": { "deviceNumber": 1, "microstepUm": 0 } }""", "x.microstepUm must be above 0" },
        { """{ "stageBaudRate": 115200 }""", "stageBaudRate must be 9600" },
        { """{ "spotDiameterUm": -1 }""", "spotDiameterUm must be a finite number above 0" },
        { """{ "gate": { "watchdogMs": 1e12 } }""", "gate.watchdogMs has a value of the wrong type or out of range for it (line 1, column 31)" },
        { """{ "gate": { "watchdogMs": "soon" } }""", "gate.watchdogMs has a value of the wrong type" },
        { """{ "gate": { "WatchdogMs": 0 } }""", ": gate.WatchdogMs is not a field of the machine profile (line 1, column 26)" },
        { """{ "watchdogMs": 100 }""", ": watchdogMs is not a field of the machine profile (line 1, column 16)" },
        { """{ "scanOffsets": [ { "speedMmPerS": 2, "offsetUm": 5 }, { "speedMmPerS": 1, "offsetUm": 3 } ] }""", "scanOffsets[1].speedMmPerS must be above scanOffsets[0].speedMmPerS 2 mm/s: list the speeds in increasing order, each once (got 1)" },
        { """{ "scanOffsets": [ { "speedMmPerS": 1, "offsetUm": 5 }, { "speedMmPerS": 1, "offsetUm": 3 } ] }""", "scanOffsets[1].speedMmPerS must be above scanOffsets[0].speedMmPerS 1 mm/s" },
        { """{ "scanOffsets": [ { "speedMmPerS": 0, "offsetUm": 5 } ] }""", "scanOffsets[0].speedMmPerS must be a finite speed above 0 mm/s (got 0)" },
        { """{ "scanOffsets": [ { "speedMmPerS": 1, "offsetUm": -1500 } ] }""", "scanOffsets[0].offsetUm must be finite and at most 1000 µm either way (got -1500)" },
        { """{ "scanOffsets": [ { "speedMmPerS": 1, "offsetUm": 1e400 } ] }""", "scanOffsets[0].offsetUm must be finite and at most 1000 µm either way (got Infinity)" },
        { """{ "scanOffsets": [ null ] }""", "scanOffsets[0] must not be null: give speedMmPerS and offsetUm" },
        { """{ "scanOffsets": [ { "speed": 1, "offsetUm": 2 } ] }""", "is not a field of the machine profile" },
        { """{ "z": { "deviceNumber": 1 } }""", "z.deviceNumber and x.deviceNumber cannot both be 1: the focus axis is a device of its own on the chain" },
        { """{ "z": { "deviceNumber": 0 } }""", "z.deviceNumber must be 1..254" },
        { """{ "z": { "microstepUm": 0 } }""", "z.microstepUm must be above 0" },
        { """{ "z": { "maxSpeedMmPerS": 40 } }""", "z.maxSpeedMmPerS must be 0.00093..30.47907 mm/s" },
        { """{ "z": { "speedMmPerS": 3 } }""", "z.speedMmPerS must be 0.00093..2 mm/s, one speed unit up to z.maxSpeedMmPerS (got 3)" },
        { """{ "z": { "minMm": 25 } }""", "z.minMm must be 0 or more and below z.travelMm 25 mm (got 25)" },
        { """{ "z": { "maxMm": 26 } }""", "z.maxMm must be above z.minMm 0 mm and at most z.travelMm 25 mm (got 26)" },
        { """{ "z": { "minMm": 5, "maxMm": 10 } }""", "z.focusMm must be within z.minMm..z.maxMm 5..10 mm (got 12.5)" },
        { """{ "z": { "focusmm": 10 } }""", "z.focusmm is not a field of the machine profile" },
        { """{ "gate": { "kind": "frequencyOnly" } }""", "gate.watchdogMs must be 0 for a frequencyOnly gate: such a gate has no watchdog, and the profile must say so (got 1000)" },
        { """{ "gate": { "kind": "frequencyOnly", "watchdogMs": 0, "offCommand": "FREQ 1" } }""", "gate.offCommand \"FREQ 1\" begins like gate.frequencyCommand" },
        { """{ "gate": { "kind": "frequencyOnly", "watchdogMs": 0, "frequencyReply": null } }""", "gate.frequencyReply must not be null" },
        { """{ "gate": { "kind": "frequencyOnly", "watchdogMs": 0, "offCommand": "" } }""", "gate.offCommand must not be empty" },
        { """{ "gate": { "kind": "burst" } }""", "gate.kind has a value of the wrong type or out of range for it" },
        { """{ "gate": { "kind": 1 } }""", "gate.kind has a value of the wrong type or out of range for it" },
        { """{ "gate": { "neverReplies": true } }""", "gate.neverReplies must be false for a countedBurst gate" },
        { """[1, 2]""", "not a valid machine profile (line 1, column 2): expected a JSON object" },
        { """null""", "the machine profile is empty" },
        { "", "not valid JSON at line 1, column 1: the file is empty" },
    };

    [Fact]
    public void Problems_TheDefaultProfile_HasNone()
    {
        Assert.Empty(MachineProfileValidator.Problems(MachineProfile.Default));
        MachineProfile.Default.Validate();
    }

    [Theory]
    [InlineData("frequency-only.json", false)]
    [InlineData("frequency-only-silent.json", true)]
    public void Load_FrequencyOnlyExampleProfile_AFrequencyOnlyGateWithoutWatchdog(string file, bool neverReplies)
    {
        var profile = MachineProfile.Load(Logging.TestRuns.Asset(Path.Combine("profiles", file)));

        Assert.Equal(LaserGateKind.FrequencyOnly, profile.Gate.Kind);
        Assert.False(profile.Gate.CountsBursts);
        Assert.False(profile.Gate.HasWatchdog);
        Assert.Equal(neverReplies, profile.Gate.NeverReplies);
        Assert.False(profile.Gate.Identifies);
        Assert.Equal("FREQ 0", profile.Gate.OffCommand);
    }

    [Fact]
    public void Problems_FrequencyOnlyGateWithUnusedCommandsEmpty_HasNone()
    {
        // A frequency-only gate is never sent STATE?, PING, WDOG or BURST: their strings may be anything, even empty.
        var gate = new LaserGateProfile
        {
            Kind = LaserGateKind.FrequencyOnly, WatchdogMs = 0, OffCommand = "FREQ 0", StatusCommand = "", KeepAliveCommand = "", WatchdogCommand = "", BurstCommand = "",
            StatusReply = "", KeepAliveReply = "", WatchdogReply = "", BurstReply = "",
        };

        Assert.Empty(MachineProfileValidator.Problems(MachineProfile.Default with { Gate = gate }));
    }

    [Fact]
    public void Problems_CountedBurstGateWithEmptyBurstCommand_NamesIt()
    {
        var gate = new LaserGateProfile { BurstCommand = "" };

        Assert.Contains("gate.burstCommand must not be empty", MachineProfileValidator.Problems(MachineProfile.Default with { Gate = gate }));
    }

    [Fact]
    public void ToJson_DefaultGate_LeavesKindAndNeverRepliesOut()
    {
        // Existing profiles and run logs are written as before: the default kind says nothing new.
        var json = MachineProfile.Default.ToJson();

        Assert.DoesNotContain("\"kind\"", json, StringComparison.Ordinal);
        Assert.DoesNotContain("neverReplies", json, StringComparison.Ordinal);
    }

    [Fact]
    public void ToJson_FrequencyOnlyGate_WritesItsKindByName()
    {
        var profile = MachineProfile.Default with { Gate = new LaserGateProfile { Kind = LaserGateKind.FrequencyOnly, WatchdogMs = 0, OffCommand = "FREQ 0" } };

        Assert.Contains("\"kind\": \"frequencyOnly\"", profile.ToJson(), StringComparison.Ordinal);
    }

    [Theory]
    [MemberData(nameof(BadProfiles))]
    public void Load_BadField_OneLineNamingTheFileAndTheField(string json, string expected)
    {
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);
            var ex = Assert.Throws<ProfileException>(() => MachineProfile.Load(path));
            Assert.StartsWith($"{path}: ", ex.Message, StringComparison.Ordinal);
            Assert.Contains(expected, ex.Message, StringComparison.Ordinal);
            Assert.DoesNotContain('\n', ex.Message);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Load_ProfileWithEveryFieldSaved_LoadsBack()
    {
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            var profile = MachineProfile.Default with { MaxFrameFrequencyHz = 20, Gate = new LaserGateProfile { MaxFrequencyHz = 50000, WatchdogMs = 500 } };
            profile.Save(path);
            Assert.Equal(profile with { X = MachineProfile.Default.X, Y = MachineProfile.Default.Y, Gate = profile.Gate }, MachineProfile.Load(path) with { X = MachineProfile.Default.X, Y = MachineProfile.Default.Y, Gate = profile.Gate });
            Assert.Equal(500, MachineProfile.Load(path).Gate.WatchdogMs);
            Assert.Equal(20, MachineProfile.Load(path).MaxFrameFrequencyHz);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Load_ScanOffsets_LoadBackInOrder()
    {
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            var profile = MachineProfile.Default with { ScanOffsets = [new ScanOffset(0.5, 2), new ScanOffset(2, 9.5)] };
            profile.Save(path);

            var loaded = MachineProfile.Load(path);

            Assert.Equal(profile.ScanOffsets, loaded.ScanOffsets);
            Assert.Equal(5.75, loaded.ScanOffsetUmAt(1.25), 12);
            Assert.DoesNotContain("scanOffsets", MachineProfile.Default.ToJson(), StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Load_ThreeAxisExample_HasTheFocusAxisAndSavesBackWithIt()
    {
        var example = Imaging.StarterAssetsTests.Asset(Path.Combine("profiles", "three-axis.json"));
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            var profile = MachineProfile.Load(example);
            var z = Assert.IsType<ZAxisProfile>(profile.Z);
            Assert.Equal((3, 12.5, 5.0, 20.0), (z.DeviceNumber, z.FocusMm, z.MinMm, z.UpperMm));

            profile.Save(path);

            Assert.Equal(z, MachineProfile.Load(path).Z);
            Assert.DoesNotContain("\"z\"", MachineProfile.Default.ToJson(), StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Validate_ProfileBuiltInCode_RefusesANullSection()
    {
        var profile = MachineProfile.Default with { Gate = null! };

        var ex = Assert.Throws<ProfileException>(() => profile.Validate("app"));

        Assert.Equal("app: gate must not be null: give the section or leave it out for the defaults", ex.Message);
    }

    [Fact]
    public void Limits_TheDefaultProfile_AreTheDevicesAndTheProfilesBounds()
    {
        var limits = MachineLimits.Of(MachineProfile.Default);

        Assert.Equal(4, limits.MaxSpeedMmPerS);
        Assert.Equal(200, limits.MaxAccelerationMmPerS2);
        Assert.Equal(100000, limits.MaxFrequencyHz);
        Assert.Equal(100, limits.MaxFrameFrequencyHz);
        Assert.Equal(9.375 * 0.09921875 / 1000, limits.MinSpeedMmPerS, 12);
        Assert.False(limits.SpeedAllowed(double.NaN));
        Assert.False(limits.FrequencyAllowed(0.4));
        Assert.True(limits.FrequencyAllowed(0.5));
    }
}
