using Bunit;
using LaserEngrave.App.Services;
using LaserEngrave.App.Tests.ViewModels;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using Microsoft.AspNetCore.Components;
using Microsoft.Extensions.DependencyInjection;
using Microsoft.FluentUI.AspNetCore.Components;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

/// <summary>A component on bunit's renderer over view-models built on fakes (machine, run service, log store, files).</summary>
public abstract class ComponentTest : BunitContext
{
    private protected ComponentTest()
    {
        Store.History().Returns([]);
        Store.Folder.Returns("/logs");
        Store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
        Settings.Load().Returns(new AppSettings());
        Files.SampleImages().Returns([TestFiles.Asset("qr-code.bmp"), TestFiles.Asset("text-banner.png")]);
        Main = new MainViewModel(new ImageService(), Machine.Factory, Runs, Store, Settings, Files, TimeProvider.System, new MachineActivity(), new JobFiles(new AppFolders(DataFolder.Path)));
        Services.AddFluentUIComponents();
        Services.AddSingleton(Files);
        Services.AddSingleton(Main);
        PresetStore.Load().Returns(ProcessPreset.Examples);
        Presets = new PresetsViewModel(PresetStore, Main.Job);
        Services.AddSingleton(Presets);
        Calibration = new CalibrationViewModel(Main, DataFolder.Path);
        Services.AddSingleton(Calibration);
        Alignment = new AlignmentViewModel(Main, DataFolder.Path);
        Services.AddSingleton(Alignment);
        Camera = new CameraViewModel(new CameraService(Main));
        Services.AddSingleton(Camera);
        Marks = new MarkViewModel(new MarkService(new AppFolders(DataFolder.Path), () => Main.Job.Profile, TimeProvider.System), path => Main.Layers.Open(path));
        Services.AddSingleton(Marks);
        Commission = new CommissionViewModel(Main, Checks, DataFolder.Path, TimeProvider.System);
        Services.AddSingleton(Commission);
        JSInterop.Mode = JSRuntimeMode.Loose;
        SetRendererInfo(new RendererInfo("Server", isInteractive: true));
    }

    private protected Fakes Machine { get; } = new();

    private protected CameraViewModel Camera { get; }

    /// <summary>The machine check the Commission panel runs (a fake: the steps are what a test reports).</summary>
    private protected IMachineCheckService Checks { get; } = Substitute.For<IMachineCheckService>();

    private protected CommissionViewModel Commission { get; }

    private protected IRunService Runs { get; } = Substitute.For<IRunService>();

    private protected IRunLogStore Store { get; } = Substitute.For<IRunLogStore>();

    private protected ISettingsStore Settings { get; } = Substitute.For<ISettingsStore>();

    private protected IFileAccess Files { get; } = Substitute.For<IFileAccess>();

    private protected MainViewModel Main { get; }

    private protected IPresetStore PresetStore { get; } = Substitute.For<IPresetStore>();

    private protected PresetsViewModel Presets { get; }

    /// <summary>The app's data folder in these tests (the calibration writes its pattern and profile there).</summary>
    private protected TestFiles.TempFolder DataFolder { get; } = TestFiles.NewFolder();

    private protected CalibrationViewModel Calibration { get; }

    private protected AlignmentViewModel Alignment { get; }

    /// <summary>The Mark panel's view-model, over the real marks service in <see cref="DataFolder"/>.</summary>
    private protected MarkViewModel Marks { get; }

    protected override void Dispose(bool disposing)
    {
        if (disposing)
        {
            DataFolder.Dispose();
        }

        base.Dispose(disposing);
    }

    // xunit disposes the context asynchronously, which does not go through Dispose(bool): the folder is removed here too.
    protected override async ValueTask DisposeAsyncCore()
    {
        await base.DisposeAsyncCore();
        DataFolder.Dispose();
    }

    private protected static MachineProfile Profile => MachineProfile.Default;

    private protected void OpenQr(double widthMm = 5)
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        Main.Job.EditWidth(widthMm);
    }

    private protected Task ConnectAsync() => Main.Machine.ConnectCommand.ExecuteAsync(null);

    private protected static bool Disabled(AngleSharp.Dom.IElement element) => element.HasAttribute("disabled");
}
