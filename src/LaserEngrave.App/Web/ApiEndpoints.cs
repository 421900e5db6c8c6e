using System.Text;
using System.Text.Json;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using CommunityToolkit.Mvvm.Input;
using Microsoft.AspNetCore.Http.Features;
using Microsoft.AspNetCore.Http.HttpResults;

namespace LaserEngrave.App.Web;

/// <summary>The page's JSON API: each request sets a view-model value or starts a command, and answers with the new state.</summary>
/// <remarks>Machine commands are started, not awaited: the page follows them over the event stream, so no request waits on a port.</remarks>
internal static class ApiEndpoints
{
    private const int MaxPreviewSidePx = 1024;
    private const int MaxPlanMoves = 400_000;

    public static void Map(IEndpointRouteBuilder app)
    {
        var api = app.MapGroup("/api");

        // Every bound body checks its own values (finite numbers, known names) before the route touches anything.
        api.AddEndpointFilter(ApiRequests.CheckAsync);

        // The interlock's refusal, wherever it is raised: 409 and the one line saying what is running.
        api.AddEndpointFilter(async (context, next) =>
        {
            try
            {
                return await next(context).ConfigureAwait(false);
            }
            catch (MachineBusyException ex)
            {
                return Busy(ex.Message);
            }
        });

        api.MapGet("/state", (MainViewModel main) => Results.Json(StateSnapshot.From(main), ApiRequests.StateJson))
            .WithSummary("The whole state: image, job, estimate, machine, test moves, run, log, and what holds the machine (activity).");

        api.MapPost("/image", UploadAsync)
            .WithSummary("Keeps the request body (the file's bytes) under the data folder's images/ and opens it; ?name= is its file name.");
        api.MapPost("/image/open", (MainViewModel main, PathRequest request, CancellationToken cancellationToken) => OpenImageAsync(main, request.Path, cancellationToken))
            .WithSummary("Opens an image or drawing file on this computer (regular files only); answers once it is read and planned.");
        api.MapGet("/image/original.png", (MainViewModel main) =>
            main.Job.OriginalPreviewPng() is { } png ? Results.File(png, "image/png") : Results.NotFound())
            .WithSummary("The image, at most 1024 px on its longer side.");
        api.MapGet("/image/mask.png", (MainViewModel main, IImageService images) =>
            main.Job.Mask is { } mask ? Results.File(images.RenderMaskPng(mask, MaxPreviewSidePx), "image/png") : Results.NotFound())
            .WithSummary("The mask (black = burn), at most 1024 px.");

        api.MapPost("/job", (MainViewModel main, Dictionary<string, JsonElement> changes) => EditJob(main, changes))
            .WithSummary("Changes job values ({\"widthMm\": 20, \"laserFrequencyHz\": 5000, ...}; fields in docs/api.md) and plans once; 400 names each unusable field.");
        api.MapGet("/plan", (MainViewModel main) => Plan(main))
            .WithSummary("The plan's moves as [kind, x0, y0, x1, y1, ...] in microsteps, with the travel and the job's edges.");

        api.MapGet("/ports", (MainViewModel main) =>
        {
            main.Machine.RefreshPorts();
            return Results.Json(main.Machine.Ports);
        })
            .WithSummary("The serial ports.");
        api.MapPost("/machine/connect", (MainViewModel main, ConnectRequest request) =>
        {
            if (Refused(main, main.Machine.ConnectCommand) is { } refused)
            {
                return refused;
            }

            main.Machine.UseSimulator = request.UseSimulator;
            main.Machine.StagePort = request.StagePort;
            main.Machine.LaserPort = request.LaserPort;
            return Start(main, main.Machine.ConnectCommand);
        })
            .WithSummary("202; connects (the simulator, or the stage and laser ports) and reads both axes and the gate.");
        api.MapPost("/machine/disconnect", (MainViewModel main) => Start(main, main.Machine.DisconnectCommand))
            .WithSummary("202; disconnects.");
        api.MapPost("/machine/identify", (MainViewModel main) => Start(main, main.Machine.IdentifyCommand))
            .WithSummary("202; reads the devices' identity and state again.");
        api.MapPost("/machine/home", (MainViewModel main) => Start(main, main.Machine.HomeCommand))
            .WithSummary("202; laser off, both axes home.");

        api.MapPost("/moves/jog", (MainViewModel main, JogRequest request) =>
        {
            if (Refused(main, main.TestMoves.JogCommand, request.Direction) is { } refused)
            {
                return refused;
            }

            if (request.StepUm is { } step)
            {
                main.TestMoves.StepUm = step;
            }

            // The job rules' sentence, as the page and the command line's jog say it.
            return main.TestMoves.JogProblem(request.Direction) is { } problem ? Unusable(problem) : Start(main, main.TestMoves.JogCommand, request.Direction);
        })
            .WithSummary("202; a step in x+, x-, y+ or y- (up to the axis' travel); 400 with the rule's sentence for a step the stage cannot make.");
        api.MapPost("/moves/goto", (MainViewModel main, GoToRequest request) =>
        {
            if (Refused(main, main.TestMoves.GoToCommand) is { } refused)
            {
                return refused;
            }

            main.TestMoves.GoToXMm = request.XMm;
            main.TestMoves.GoToYMm = request.YMm;
            return main.TestMoves.GoToProblem is { } problem ? Unusable(problem) : Start(main, main.TestMoves.GoToCommand);
        })
            .WithSummary("202; moves to a position in mm, laser off; 400 with the rule's sentence for a position off the travel.");
        api.MapPost("/moves/origin", (MainViewModel main) => Start(main, main.TestMoves.GoToOriginCommand))
            .WithSummary("202; to the job's top-left corner, laser off.");
        api.MapPost("/moves/frame", (MainViewModel main) => Start(main, main.TestMoves.FrameCommand))
            .WithSummary("202; traces the job's outline, laser off.");
        api.MapPost("/moves/fire", (MainViewModel main, FireRequest request) =>
        {
            if (Refused(main, main.TestMoves.TestFireCommand) is { } refused)
            {
                return refused;
            }

            main.TestMoves.TestFirePulses = request.Pulses;
            return main.TestMoves.TestFireProblem is { } problem ? Unusable(problem) : Start(main, main.TestMoves.TestFireCommand);
        })
            .WithSummary("202; a burst of pulses (1 to 1,000,000, the gate's burst range) at the job's frequency where the stage stands; 400 with the rule's sentence outside it.");
        api.MapPost("/moves/stop", (MainViewModel main) => Do(main, main.TestMoves.StopCommand.Execute))
            .WithSummary("Stops the test move, jog or homing under way (laser off).");

        api.MapPost("/run/start", (MainViewModel main, RunStartRequest request) =>
        {
            if (main.Run.IsActive)
            {
                return Ignored(main, "a run is already under way: this Start was ignored");
            }

            // A gate without a watchdog runs once accepted, here as by the Machine panel's checkbox (the log keeps it).
            if (request.AcceptNoWatchdog)
            {
                main.Machine.AcceptNoWatchdog = true;
            }

            if (main.Machine.NoWatchdogUnaccepted is not null)
            {
                return Busy($"{LaserGateProfile.NoWatchdogSentence}; send \"acceptNoWatchdog\": true to accept it (or tick it in the Machine panel)");
            }

            if (Refused(main, main.Run.StartCommand) is { } refused)
            {
                return refused;
            }

            // A burn speed the job refuses (one this computer cannot hold with this gate, a pixel too short for it): the
            // sentence under the page's speed field, before anything moves.
            if (main.Job.Errors.TryGetValue(JobViewModel.BurnSpeedField, out var speed))
            {
                return Busy(speed);
            }

            // A run the run use case refuses (nothing to burn, outside the travel, no machine, a log folder that takes no
            // file, marks burned already) is refused here as a refusal, with its reason, before anything moves.
            if (main.Run.StartRefusal() is { } refusal)
            {
                return Busy(refusal);
            }

            // A job longer than the user's threshold (an hour until set), or of pixels much smaller than the spot, asks as the page's Start does.
            if (!request.Confirm && main.Run.StartQuestion is { } question)
            {
                return Busy($"{question} Send \"confirm\": true to start anyway");
            }

            main.Log.Notes = request.Notes;
            main.Log.SampleId = request.SampleId;
            return Start(main, main.Run.ConfirmStartCommand);
        })
            .WithSummary("202; runs the planned job (all passes); a second start during a run is ignored (200 with a note); 409 with the question for a job longer than the Machine panel's \"Ask before runs longer than\" (an hour until set) or of pixels much smaller than the spot, unless confirm is true; 409 with the sentence for a gate without a watchdog, unless acceptNoWatchdog is true (or the Machine panel's box is ticked); 409 with the burn speed field's sentence when the job refuses its speed (one this computer cannot hold with this gate); 409 with the reason when the run is refused before it starts (no job, nothing to burn, outside the travel, not connected, a log folder that takes no file, marks burned already).");
        api.MapPost("/run/continue", (MainViewModel main) =>
        {
            if (main.Run.IsActive)
            {
                return Ignored(main, "a run is already under way: this Continue was ignored");
            }

            return main.Run.ContinueUnavailableReason is { } reason ? Busy(reason)
                : main.Run.StoppedAt is null ? Busy("no stopped run to continue: the last run completed, or none ran")
                : Start(main, main.Run.ContinueCommand);
        })
            .WithSummary("202; continues the stopped run; 409 with the reason when it cannot.");
        api.MapPost("/run/pause", (MainViewModel main) => Do(main, main.Run.PauseCommand.Execute))
            .WithSummary("Pauses the run after the current move.");
        api.MapPost("/run/resume", (MainViewModel main) => Do(main, main.Run.ResumeCommand.Execute))
            .WithSummary("Resumes a paused run.");
        api.MapPost("/run/abort", (MainViewModel main) => Do(main, main.Run.AbortCommand.Execute))
            .WithSummary("Aborts the run: laser off first, then the stage stops; the log is written.");

        api.MapPost("/logs/load", (MainViewModel main, PathRequest request) =>
        {
            main.Activity.ThrowIfJobLocked();
            return Do(main, _ => main.Log.LoadCommand.Execute(request.Path ?? string.Empty));
        })
            .WithSummary("Puts a past run's image and values back.");
        api.MapPost("/logs/open-folder", (MainViewModel main) => Do(main, main.Log.OpenFolderCommand.Execute))
            .WithSummary("Opens the log folder on this computer's screen.");
        api.MapGet("/logs/export", (MainViewModel main, string path, string? format) => Export(main, path, format))
            .WithSummary("A logged run's file (format=json or txt); only runs the history lists.");

        api.MapGet("/logs/history", (MainViewModel main, string? format, string? decimalMark) => ExportHistory(main, format, decimalMark))
            .WithSummary("The runs ticked in the history table as CSV (decimalMark=comma: decimal commas, fields between semicolons) or format=json.");

        api.MapGet("/jobfile", (MainViewModel main) => main.Layers.ToDownload() is { } bytes
                ? Results.File(bytes, "application/json", main.Layers.DownloadName)
                : Busy(main.Layers.FileError ?? "nothing to save"))
            .WithSummary("The job file of the job now (the layers, or the open image or drawing as one layer), sources as full paths; the page's Download job file. 409 with the reason when there is nothing to save.");
        api.MapPost("/jobfile/open", (MainViewModel main, PathRequest request) => JobFile(main, request.Path, main.Layers.Open))
            .WithSummary("Opens a job file on this computer by its path: one layer opens as the single job, more as the layers; 400 with the file's problem.");
        api.MapPost("/jobfile/save", (MainViewModel main, PathRequest request) => JobFile(main, request.Path, main.Layers.Save))
            .WithSummary("Saves the job (the layers, or the open image or drawing as one layer) as a job file at the path given (.json), sources relative to it; 400 with the reason.");

        api.MapPost("/settings/theme", (MainViewModel main, ThemeRequest request) => main.SetTheme(request.Theme)
                ? State(main)
                : Results.Json(new { error = $"theme '{ApiRequests.Quote(request.Theme)}': use {string.Join(", ", MainViewModel.Themes)}" }, statusCode: StatusCodes.Status400BadRequest))
            .WithSummary("The theme: system, light or dark.");
    }

    private static JsonHttpResult<object> State(MainViewModel main) => TypedResults.Json(StateSnapshot.From(main), ApiRequests.StateJson);

    private static JsonHttpResult<object> Do(MainViewModel main, Action<object?> action)
    {
        action(null);
        return State(main);
    }

    /// <summary>Opens or saves a job file by its path: the state, or 400 with the file's problem.</summary>
    private static IResult JobFile(MainViewModel main, string? path, Func<string, bool> action) =>
        string.IsNullOrWhiteSpace(path)
            ? Results.Json(new { error = "give the job file's path: \"path\": \"…/job.json\"" }, statusCode: StatusCodes.Status400BadRequest)
            : action(path)
                ? State(main)
                : Results.Json(new { error = main.Layers.FileError }, statusCode: StatusCodes.Status400BadRequest);

    /// <summary>409 with the one line saying what holds the machine (or why the request cannot be done now).</summary>
    /// <summary>A value the rules refuse: 400 and their one line, nothing started.</summary>
    private static IResult Unusable(string message) => Results.Json(new { error = message }, statusCode: StatusCodes.Status400BadRequest);

    private static IResult Busy(string message) => Results.Json(new { error = message }, statusCode: StatusCodes.Status409Conflict);

    /// <summary>A request that changed nothing on purpose (a second Start during a run): 200, the note and the state.</summary>
    private static IResult Ignored(MainViewModel main, string note) => Results.Json(new { note, state = StateSnapshot.From(main) }, ApiRequests.StateJson);

    /// <summary>
    /// The 409 answer when the interlock disables <paramref name="command"/> now; null when it may start. A command the
    /// page only greys out for the state (not connected, no job) still starts and reports why it failed in the state.
    /// </summary>
    private static IResult? Refused(MainViewModel main, IAsyncRelayCommand command, object? parameter = null) =>
        command.CanExecute(parameter) || main.Activity.BusyMessage is not { } busy ? null : Busy(busy);

    /// <summary>Answers once the command has started (202); its end shows in the state. Refused with 409 while the interlock disables it.</summary>
    private static IResult Start(MainViewModel main, IAsyncRelayCommand command, object? parameter = null)
    {
        if (Refused(main, command, parameter) is { } refused)
        {
            return refused;
        }

        // The command catches what the user can cause; anything else is still observed here, not lost.
        _ = command.ExecuteAsync(parameter).ContinueWith(t => _ = t.Exception, TaskScheduler.Default);
        return TypedResults.Json(StateSnapshot.From(main), ApiRequests.StateJson, statusCode: StatusCodes.Status202Accepted);
    }

    /// <summary>Opens the file as the page does, read and planned in the background with its progress in the state; the request waits for it.</summary>
    private static async Task<IResult> OpenImageAsync(MainViewModel main, string? path, CancellationToken cancellationToken)
    {
        main.Activity.ThrowIfJobLocked();
        await main.Job.LoadImageAsync(path ?? string.Empty, cancellationToken).ConfigureAwait(false);
        return State(main);
    }

    /// <summary>Keeps the page's file under the app's image folder and opens it; one limit, the app's, with its own message.</summary>
    private static async Task<IResult> UploadAsync(HttpRequest request, MainViewModel main, IFileAccess files, string? name)
    {
        main.Activity.ThrowIfJobLocked();
        // The name as sent: a path is refused (400), never cut down to its last part.
        var fileName = name ?? "image";
        if (request.ContentLength is > IFileAccess.MaxUploadBytes)
        {
            return TooLarge(new UploadException(fileName, Services.FileAccess.TooLarge).Message);
        }

        // Above Kestrel's limit by one byte, so the app's own rule, not the server's empty 413, answers a larger body.
        if (request.HttpContext.Features.Get<IHttpMaxRequestBodySizeFeature>() is { IsReadOnly: false } limit)
        {
            limit.MaxRequestBodySize = IFileAccess.MaxUploadBytes + 1;
        }

        string path;
        try
        {
            // A run started while the body streamed in refuses it here (409), before anything is put in place.
            path = await files.SaveUploadAsync(fileName, request.Body, request.HttpContext.RequestAborted, main.Activity.ThrowIfJobLocked).ConfigureAwait(false);
        }
        catch (UploadException ex)
        {
            return ex.Message.EndsWith(Services.FileAccess.TooLarge, StringComparison.Ordinal) ? TooLarge(ex.Message)
                : ex.QuotaExceeded ? Results.Json(new { error = ex.Message }, statusCode: StatusCodes.Status507InsufficientStorage)
                : Results.Json(new { error = ex.Message }, statusCode: StatusCodes.Status400BadRequest);
        }

        if (!await main.Job.LoadImageAsync(path, request.HttpContext.RequestAborted).ConfigureAwait(false))
        {
            // Only files that open stay in images/; why it did not open is in the state's errors.
            main.Job.NameUploadInError(path, fileName);
            files.RemoveUpload(path);
        }

        return State(main);
    }

    private static IResult TooLarge(string message) => Results.Json(new { error = message }, statusCode: StatusCodes.Status413PayloadTooLarge);

    private static IResult EditJob(MainViewModel main, Dictionary<string, JsonElement> changes)
    {
        var job = main.Job;
        var problems = new Dictionary<string, string>();
        job.Batch(() =>
        {
            foreach (var (field, value) in changes)
            {
                var name = ApiRequests.Quote(field);
                try
                {
                    Set(job, field, value);
                }
                catch (UnusableValueException ex)
                {
                    problems[name] = $"{name}: {ex.Message}";
                }
                catch (Exception ex) when (ex is InvalidOperationException or FormatException or ArgumentException)
                {
                    problems[name] = $"{name}: '{ApiRequests.Quote(value.GetRawText())}' is not a usable value";
                }
            }
        });

        // A value the job rules refuse stays, as the page's field keeps it beside its sentence: 400 with that sentence,
        // so a client hears the same refusal as the page and the command line (Start stays refused until it changes).
        foreach (var field in changes.Keys)
        {
            var shownBeside = field switch
            {
                "originXMm" or "originYMm" => JobViewModel.OriginField,
                "microstepsPerPixel" => JobViewModel.PitchField,
                _ => field,
            };
            if (!problems.ContainsKey(ApiRequests.Quote(field)) && job.Errors.TryGetValue(shownBeside, out var refused))
            {
                problems[ApiRequests.Quote(field)] = refused;
            }
        }

        return problems.Count == 0 ? State(main) : Results.Json(new { errors = problems, state = StateSnapshot.From(main) }, ApiRequests.StateJson, statusCode: 400);
    }

    private static void Set(JobViewModel job, string field, JsonElement value)
    {
        switch (field)
        {
            case "thresholdPercent": job.ThresholdPercent = Number(value); break;
            case "dither": job.Dither = Named<DitherMethod>(value); break;
            case "invert": job.Invert = Bool(value); break;
            case "aspectLocked": job.AspectLocked = Bool(value); break;
            case "widthMm": job.EditWidth(Number(value)); break;
            case "heightMm": job.EditHeight(Number(value)); break;
            case "pitchUm": job.EditPitch(Number(value)); break;
            case "microstepsPerPixel": job.EditMicrostepsPerPixel(Number(value)); break;
            case "originXMm": job.OriginXMm = Number(value); break;
            case "originYMm": job.OriginYMm = Number(value); break;
            case "laserFrequencyHz": job.LaserFrequencyHz = Number(value); break;
            case "burnSpeedMmPerS": job.BurnSpeedMmPerS = Number(value); break;
            case "travelSpeedMmPerS": job.TravelSpeedMmPerS = Number(value); break;
            case "accelerationMmPerS2": job.AccelerationMmPerS2 = Number(value); break;
            case "strategy": job.Strategy = Named<PlanStrategy>(value); break;
            case "bidirectional": job.Bidirectional = Bool(value); break;
            case "overscanMm": job.OverscanMm = Number(value); break;
            case "passes": job.Passes = (int)Whole(value, int.MaxValue); break;
            case "mode": job.Mode = Named<PlanMode>(value); break;
            case "pulsesPerDot": job.PulsesPerDot = (int)Whole(value, int.MaxValue); break;
            case "dotPitchMicrosteps": job.DotPitchMicrosteps = Whole(value, long.MaxValue); break;
            case "dotSettleMs": job.DotSettleMs = Number(value); break;
            case "pulseEnergyUj": job.PulseEnergyUj = value.ValueKind == JsonValueKind.Null ? null : Number(value); break;
            case "quarterTurns": job.QuarterTurns = (int)Whole(value, 3); break;
            case "mirrorX": job.MirrorX = Bool(value); break;
            case "mirrorY": job.MirrorY = Bool(value); break;
            default: throw new UnusableValueException($"not a job field (docs/api.md lists them)");
        }
    }

    /// <summary>A finite JSON number (never a string, never one too large for a double, which reads as infinity).</summary>
    private static double Number(JsonElement value) =>
        value.ValueKind == JsonValueKind.Number && value.TryGetDouble(out var v) && double.IsFinite(v) ? v
        : throw new UnusableValueException(value.ValueKind == JsonValueKind.Number
            ? $"{ApiRequests.Quote(value.GetRawText())} is not a finite number"
            : $"'{ApiRequests.Quote(value.ToString())}' is not a number (send a JSON number, without quotes)");

    private static long Whole(JsonElement value, long max) =>
        value.ValueKind == JsonValueKind.Number && value.TryGetInt64(out var v) && v >= 0 && v <= max ? v
        : throw new UnusableValueException($"{ApiRequests.Quote(value.ValueKind == JsonValueKind.String ? $"'{value}'" : value.GetRawText())} is not a whole number from 0 to {max}");

    private static bool Bool(JsonElement value) =>
        value.ValueKind is JsonValueKind.True or JsonValueKind.False ? value.GetBoolean()
        : throw new UnusableValueException($"{ApiRequests.Quote(value.GetRawText())} is not true or false");

    /// <summary>One of the enum's names (any case); a number, or a name the enum does not define, is refused, so nothing undefined is kept.</summary>
    private static T Named<T>(JsonElement value)
        where T : struct, Enum =>
        value.ValueKind == JsonValueKind.String && value.GetString() is { Length: > 0 } text && char.IsAsciiLetter(text[0]) && !text.Contains(',', StringComparison.Ordinal)
            && Enum.TryParse<T>(text, ignoreCase: true, out var named) && Enum.IsDefined(named)
            ? named
            : throw new UnusableValueException($"'{ApiRequests.Quote(value.ToString())}' is not one of {string.Join(", ", Enum.GetNames<T>())}");

    /// <summary>A job value the API refuses, with the reason in a line.</summary>
    private sealed class UnusableValueException(string message) : Exception(message);

    /// <summary>The plan's moves as a flat list of numbers (kind, x0, y0, x1, y1 per move), for the page to draw once.</summary>
    private static IResult Plan(MainViewModel main)
    {
        var job = main.Job.Job;
        var profile = main.Job.Profile;
        var moves = new List<long>();
        var truncated = false;
        if (main.Job.Drawing is { } drawing)
        {
            // A drawing: per stroke the travel from where the last one came to rest, its run-up (laser off), then its
            // path burned vertex to vertex, one move a segment; the run's progress counts strokes.
            (long X, long Y)? at = null;
            foreach (var stroke in drawing.Schedule.Strokes)
            {
                if (moves.Count >= MaxPlanMoves * 5)
                {
                    truncated = true;
                    break;
                }

                var (start, path) = (stroke.RunUpStart, stroke.Path.Points);
                if (at is { } from)
                {
                    moves.AddRange([(long)Core.Planning.MoveKind.Travel, from.X, from.Y, start.X, start.Y]);
                }

                moves.AddRange([(long)Core.Planning.MoveKind.Travel, start.X, start.Y, path[0].X, path[0].Y]);
                for (var i = 1; i < path.Count; i++)
                {
                    moves.AddRange([(long)Core.Planning.MoveKind.Burn, path[i - 1].X, path[i - 1].Y, path[i].X, path[i].Y]);
                }

                at = (stroke.RestEnd.X, stroke.RestEnd.Y);
            }
        }
        else if (job?.Dots is { } dots)
        {
            // Dot mode: each dot as a short burn stroke a quarter of the dot spacing either side, one a dot, so the
            // run's progress (dots done) marks as many of them burned.
            var half = Math.Max(1, (long)Math.Round(dots.DotSpacingUm / dots.Geometry.MicrostepUm / 4));
            foreach (var dot in dots.Dots())
            {
                if (moves.Count >= MaxPlanMoves * 5)
                {
                    truncated = true;
                    break;
                }

                moves.AddRange([(long)Core.Planning.MoveKind.Burn, dot.X - half, dot.Y, dot.X + half, dot.Y]);
            }
        }
        else if (job is not null)
        {
            foreach (var move in job.Plan.Moves())
            {
                if (moves.Count >= MaxPlanMoves * 5)
                {
                    truncated = true;
                    break;
                }

                moves.AddRange([(long)move.Kind, move.X0, move.Y0, move.X1, move.Y1]);
            }
        }

        // The job's edges as Frame traces them, whichever kind it is.
        var box = main.Job.Engraving?.FrameBox;
        return Results.Json(new
        {
            version = main.Job.PlanVersion,
            travelX = profile.X.TravelMicrosteps,
            travelY = profile.Y.TravelMicrosteps,
            microstepUm = profile.X.MicrostepUm,
            job = box is not { } edges ? null : new { left = edges.Left, right = edges.Right, top = edges.Top, bottom = edges.Bottom },
            moves,
            truncated,
        });
    }

    /// <summary>A logged run's JSON or text file; only runs the history lists can be fetched, never any other file.</summary>
    private static IResult Export(MainViewModel main, string path, string? format)
    {
        if (main.Log.Find(path) is not { Record: { } record })
        {
            return Results.NotFound(new { error = $"{path}: not a run in the history" });
        }

        var json = string.Equals(format, "json", StringComparison.OrdinalIgnoreCase);
        var name = Path.GetFileNameWithoutExtension(path) + (json ? ".json" : ".txt");
        return json
            ? Results.File(Encoding.UTF8.GetBytes(RunRecordJson.Serialize(record)), "application/json", name)
            : Results.File(Encoding.UTF8.GetBytes(RunSummaryText.Format(record)), "text/plain; charset=utf-8", name);
    }

    private static IResult ExportHistory(MainViewModel main, string? format, string? decimalMark)
    {
        if (main.Log.SelectedRows.Count == 0)
        {
            return Results.NotFound(new { error = "no run is ticked in the history table: tick the runs to export first" });
        }

        var json = string.Equals(format, "json", StringComparison.OrdinalIgnoreCase);
                // The two CSV variants under their own names, so a download of each does not replace or rename the other.
        var comma = !json && string.Equals(decimalMark, "comma", StringComparison.OrdinalIgnoreCase);
        var name = $"runs-{DateTimeOffset.Now:yyyy-MM-dd_HHmm}{(comma ? "-decimal-comma" : "")}.{(json ? "json" : "csv")}";

        var text = main.Log.Export(json ? "json" : "csv", comma);

        // Excel reads a CSV as UTF-8 (µ, sample IDs in any script) only after the byte order mark.
        return json
            ? Results.File(Encoding.UTF8.GetBytes(text), "application/json", name)
            : Results.File([.. Encoding.UTF8.Preamble, .. Encoding.UTF8.GetBytes(text)], "text/csv; charset=utf-8", name);
    }

    internal sealed record PathRequest(string Path) : IApiRequest
    {
        public string? Problem() => string.IsNullOrWhiteSpace(Path) ? "path is empty: send the file's full path" : null;
    }

    internal sealed record ConnectRequest(bool UseSimulator, string? StagePort = null, string? LaserPort = null);

    internal sealed record JogRequest(string Direction, double? StepUm = null) : IApiRequest
    {
        public string? Problem() =>
            Direction is not ("x+" or "x-" or "y+" or "y-") ? $"direction '{ApiRequests.Quote(Direction)}' is not one of x+, x-, y+, y-"
            : ApiRequests.Finite("stepUm", StepUm);
    }

    internal sealed record GoToRequest(double XMm, double YMm) : IApiRequest
    {
        public string? Problem() => ApiRequests.Finite("xMm", XMm) ?? ApiRequests.Finite("yMm", YMm);
    }

    internal sealed record FireRequest(int Pulses);

    internal sealed record RunStartRequest(string? Notes = null, string? SampleId = null, bool Confirm = false, bool AcceptNoWatchdog = false);

    internal sealed record ThemeRequest(string Theme);
}
