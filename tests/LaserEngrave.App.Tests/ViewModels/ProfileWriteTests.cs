using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>Profile writes (calibration, commissioning) while a run holds the machine: refused before anything is written.</summary>
public sealed class ProfileWriteTests : IDisposable
{
    private const string OnDisk = "{ \"the profile on disk\": \"as the lab left it\" }";

    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly MainViewModel _main;

    public ProfileWriteTests()
    {
        var settings = Substitute.For<ISettingsStore>();
        settings.Load().Returns(new AppSettings());
        var store = Substitute.For<IRunLogStore>();
        store.History().Returns([]);
        _main = new MainViewModel(
            new ImageService(), new MachineConnectionFactory(new SimulatorOptions()), Substitute.For<IRunService>(), store, settings,
            Substitute.For<IFileAccess>(), TimeProvider.System, new MachineActivity(), new JobFiles(new AppFolders(_folder.Path)));
        File.WriteAllText(ProfilePath, OnDisk);
    }

    private string ProfilePath => Path.Combine(_folder.Path, "machine-profile.json");

    public void Dispose() => _folder.Dispose();

    [Fact]
    public void CalibrationClear_RunUnderWay_RefusedAndTheProfileOnDiskUntouched()
    {
        var calibration = new CalibrationViewModel(_main, _folder.Path);
        using var run = _main.Activity.Begin(MachineOperation.Run);

        calibration.ClearCommand.Execute(null);

        Assert.Contains("a run is under way", calibration.Error, StringComparison.Ordinal);
        Assert.Null(calibration.Status);
        Assert.Equal(OnDisk, File.ReadAllText(ProfilePath));
    }

    [Fact]
    public void SaveProfile_RunUnderWay_ThrowsBeforeWriting()
    {
        using var run = _main.Activity.Begin(MachineOperation.Run);

        Assert.Throws<MachineBusyException>(() => _main.SaveProfile(ProfilePath, MachineProfile.Default));

        Assert.Equal(OnDisk, File.ReadAllText(ProfilePath));
    }

    [Fact]
    public void CalibrationClear_Idle_WrittenAndUsed()
    {
        var calibration = new CalibrationViewModel(_main, _folder.Path);

        calibration.ClearCommand.Execute(null);

        Assert.Null(calibration.Error);
        Assert.NotEqual(OnDisk, File.ReadAllText(ProfilePath));
        Assert.Null(MachineProfile.Load(ProfilePath).Calibration);
    }
}
