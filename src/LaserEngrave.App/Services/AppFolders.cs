using LaserEngrave.Core.Logging;

namespace LaserEngrave.App.Services;

/// <summary>Where the app keeps its files: settings and uploaded images under one data folder, and the run logs.</summary>
/// <param name="DataFolder">By default LaserEngrave in the user's application-data folder.</param>
/// <param name="LogFolder">The run logs; by default the command line's folder (<see cref="RunLogStore.DefaultFolder"/>), otherwise logs/ in the data folder.</param>
public sealed record AppFolders(string DataFolder, string? LogFolder = null)
{
    public static AppFolders Default { get; } = new(
        Path.Combine(Environment.GetFolderPath(Environment.SpecialFolder.ApplicationData, Environment.SpecialFolderOption.Create), "LaserEngrave"),
        RunLogStore.DefaultFolder);

    public string SettingsFile => Path.Combine(DataFolder, "settings.json");

    /// <summary>The running app's address and token for scripts (Web/ConnectionFile), beside the settings.</summary>
    public string ConnectionFile => Path.Combine(DataFolder, "connection.json");

    /// <summary>The window's one-time launch files (Web/LaunchCodes), in a folder of the user's alone.</summary>
    public string LaunchFolder => Path.Combine(DataFolder, "launch");

    public string PresetsFile => Path.Combine(DataFolder, "presets.json");

    public string UploadFolder => Path.Combine(DataFolder, "images");

    public string RunLogFolder => LogFolder ?? Path.Combine(DataFolder, "logs");

    /// <summary>The sample images copied beside the program at build and publish (the repository's assets/).</summary>
    public string SamplesFolder { get; init; } = Path.Combine(AppContext.BaseDirectory, "samples");
}
